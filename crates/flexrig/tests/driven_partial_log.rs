//! A driven run stopped or failed midway leaves a finished log of what it computed: the
//! samples up to the stop and the error. Deterministic: the stop flag is set before the run,
//! and every driven integrator takes its first sample (t = 0) before its first check of the
//! flag, so the run ends with exactly the samples it computed and an interruption.

use std::io::Cursor;
use std::sync::atomic::AtomicBool;

use flexrig::driven::scene::DrivenScene;
use flexrig::log::mcap::LogRates;

fn scene(name: &str) -> (DrivenScene, String) {
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join(format!("../../assets/scenes/{name}.toml")),
    )
    .unwrap();
    (DrivenScene::parse(&text).unwrap(), text)
}

#[test]
fn a_stopped_driven_run_keeps_its_samples_in_its_log() {
    for name in ["driven_cj_wall", "driven_cl_free_head"] {
        let (scene, text) = scene(name);
        let stop = AtomicBool::new(true);
        let err = scene.strike.solve(Some(1e-3), &stop).unwrap_err();
        assert_eq!(err.kind(), flexrig::ErrorKind::Interrupted, "{name}: {err}");
        let flexrig::Error::Impact(ie) = &err else {
            panic!("{name}: {err:?}")
        };
        let computed = ie.partial_trace().len();
        assert!(computed >= 1, "{name}: no samples kept");
        assert!(matches!(
            ie.root(),
            flexrig_impact::ImpactError::Interrupted
        ));
        let bytes = flexrig::driven::log::write(
            Cursor::new(Vec::new()),
            &scene,
            &text,
            Err(&err),
            LogRates::DECIMATED,
        )
        .unwrap()
        .into_inner();
        let summary = mcap::Summary::read(&bytes)
            .unwrap()
            .expect("a finished log");
        let joint = mcap::MessageStream::new(&bytes)
            .unwrap()
            .filter(|m| m.as_ref().unwrap().channel.topic == "/drive/joint")
            .count();
        assert_eq!(joint, computed, "{name}: one joint message per sample");
        let error = summary
            .metadata_indexes
            .iter()
            .map(|i| mcap::read::metadata(&bytes, i).unwrap())
            .find(|r| r.name == "error")
            .expect("the error is recorded");
        assert!(error.metadata["message"].contains("stopped on request"));
    }
}
