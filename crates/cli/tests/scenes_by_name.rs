//! Bundled scenes by name wherever a scene is asked for (`run`, `sweep`, `payload`,
//! `experiment --scenes` with any subset), "did you mean" for near misses, and `flexrig scenes`
//! (the listing and `--write`).

use std::path::PathBuf;
use std::process::{Command, Output};

fn flexrig(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_flexrig"))
        .args(args)
        .output()
        .expect("the flexrig binary runs")
}

fn json(args: &[&str]) -> serde_json::Value {
    let out = flexrig(args);
    assert!(
        out.status.success(),
        "{args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("valid JSON on stdout")
}

fn scratch_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexrig-names-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn scene_path(name: &str) -> String {
    format!(
        "{}/../../assets/scenes/{name}.toml",
        env!("CARGO_MANIFEST_DIR")
    )
}

#[test]
fn run_takes_a_bundled_name_like_its_file() {
    // the same scene by name and by path: the same run, bit for bit
    let by_name = json(&["run", "cj_aluminium", "--json"]);
    let by_path = json(&["run", &scene_path("cj_aluminium"), "--json"]);
    assert_eq!(by_name["peak_force_n"], by_path["peak_force_n"]);
    assert_eq!(by_name["steps"], by_path["steps"]);
    // a near miss: exit 2, the argument, the closest name
    let o = flexrig(&["run", "cj_aluminum"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("SCENE") && stderr.contains("did you mean cj_aluminium?"),
        "{stderr}"
    );
    // no near miss: no suggestion, but the list
    let o = flexrig(&["run", "banana"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        !stderr.contains("did you mean") && stderr.contains("cl_iron"),
        "{stderr}"
    );
}

#[test]
fn payload_and_sweep_take_names_and_paths_alike() {
    let dir = scratch_dir("payload");
    let out = dir.to_str().unwrap();
    let common = ["--payloads", "0.1:1", "--points", "2", "--json"];
    let mut by_name = vec!["payload", "--scene", "cj_light_load", "--out", out];
    by_name.extend(common);
    let path = scene_path("cj_light_load");
    let mut by_path = vec!["payload", "--scene", &path, "--out", out];
    by_path.extend(common);
    assert_eq!(json(&by_name)["rows"], json(&by_path)["rows"]);
    let o = flexrig(&["payload", "--scene", "cl_light_lod", "--out", out]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("--scene") && stderr.contains("did you mean cl_light_load?"),
        "{stderr}"
    );

    // a sweep of a bundled base: its rows are the runs of that scene
    let sweep_dir = dir.join("sweep");
    let v = json(&[
        "sweep",
        "cj_iron",
        "--set",
        "robot.payload_kg=0.3",
        "--out",
        sweep_dir.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(v["rows"], 1);
    let table = std::fs::read_to_string(sweep_dir.join("sweep.csv")).unwrap();
    let alone = json(&["run", "cj_iron", "--set", "robot.payload_kg=0.3", "--json"]);
    let peak = alone["peak_force_n"].as_f64().unwrap();
    let header: Vec<&str> = table.lines().next().unwrap().split(',').collect();
    let row: Vec<&str> = table.lines().nth(1).unwrap().split(',').collect();
    let column = header.iter().position(|h| *h == "peak_force_n").unwrap();
    let swept: f64 = row[column].parse().unwrap();
    assert!(((swept - peak) / peak).abs() < 1e-12, "{swept} vs {peak}");
    let o = flexrig(&["sweep", "cj-irn", "--out", sweep_dir.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("BASE") && stderr.contains("did you mean cj_iron?"),
        "{stderr}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn scenes_lists_every_bundled_scene_and_writes_one_to_edit() {
    let v = json(&["scenes", "--json"]);
    let listed: Vec<&str> = v["scenes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["name"].as_str().unwrap())
        .collect();
    // every scene file in assets/scenes is bundled and listed, with a one-line description
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets/scenes");
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let stem = path.file_stem().unwrap().to_str().unwrap().to_string();
            assert!(listed.contains(&stem.as_str()), "{stem} is not listed");
        }
    }
    for s in v["scenes"].as_array().unwrap() {
        let summary = s["summary"].as_str().unwrap();
        assert!(!summary.is_empty() && !summary.contains('\n'), "{s}");
    }
    let text = String::from_utf8(flexrig(&["scenes"]).stdout).unwrap();
    assert!(
        text.contains("cl_light_load") && text.contains("Fig. 9a"),
        "{text}"
    );

    let out_dir = scratch_dir("write");
    let file = out_dir.join("mine.toml");
    let file_arg = file.to_str().unwrap();
    let o = flexrig(&["scenes", "--write", "cl_iron", "--out", file_arg]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(
        std::fs::read_to_string(&file).unwrap(),
        std::fs::read_to_string(scene_path("cl_iron")).unwrap()
    );
    // never overwritten without --force
    std::fs::write(&file, "edited").unwrap();
    let o = flexrig(&["scenes", "--write", "cl_iron", "--out", file_arg]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("--out") && stderr.contains("--force"),
        "{stderr}"
    );
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "edited");
    let o = flexrig(&["scenes", "--write", "cl_iron", "--out", file_arg, "--force"]);
    assert!(o.status.success());
    assert_ne!(std::fs::read_to_string(&file).unwrap(), "edited");
    // an unknown name: did you mean
    let o = flexrig(&["scenes", "--write", "cl_irn", "--out", file_arg]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("did you mean cl_iron?"), "{stderr}");
    let _ = std::fs::remove_dir_all(&out_dir);
}

#[test]
fn experiment_scenes_takes_any_subset_of_the_scene_files() {
    let dir = scratch_dir("subset");
    let scenes = dir.join("scenes");
    std::fs::create_dir_all(&scenes).unwrap();
    // one edited scene; the other nine runs use the bundled scenes
    let text = std::fs::read_to_string(scene_path("cj_light_load")).unwrap();
    let edited = text.replace("payload_kg = 0.1", "payload_kg = 0.2");
    assert_ne!(edited, text);
    std::fs::write(scenes.join("cj_light_load.toml"), edited).unwrap();
    let v = json(&[
        "experiment",
        "--repeats",
        "1",
        "--jitter-deg",
        "0",
        "--scenes",
        scenes.to_str().unwrap(),
        "--out",
        dir.join("out").to_str().unwrap(),
        "--json",
    ]);
    let group = |name: &str| {
        v["groups"]
            .as_array()
            .unwrap()
            .iter()
            .find(|g| g["scene"] == name)
            .unwrap()["mean_peak_force_n"]
            .as_f64()
            .unwrap()
    };
    let light = json(&[
        "run",
        "cj_light_load",
        "--set",
        "robot.payload_kg=0.2",
        "--json",
    ]);
    let close = |a: f64, b: f64| ((a - b) / b).abs() < 1e-12;
    let light = light["peak_force_n"].as_f64().unwrap();
    assert!(close(group("cj_light_load"), light), "{light}");
    let iron = json(&["run", "cl_iron", "--json"]);
    let iron = iron["peak_force_n"].as_f64().unwrap();
    assert!(close(group("cl_iron"), iron), "{iron}");
    // a directory with none of the scene files is a mistake, named
    let empty = dir.join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    let o = flexrig(&["experiment", "--scenes", empty.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("--scenes") && stderr.contains("cj_aluminium.toml"),
        "{stderr}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
