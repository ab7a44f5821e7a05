//! The bundled scenes (compiled in: the library and the binary need no assets directory) and
//! scene texts by name.

use std::path::{Path, PathBuf};

use flexrig_contact::Materials;
use flexrig_rig::Scene;

use crate::Error;

/// The bundled scene files, compiled in (the binary needs no assets directory).
pub const BUNDLED_SCENES: [(&str, &str); 12] = [
    (
        "cj_aluminium",
        include_str!("../../../../assets/scenes/cj_aluminium.toml"),
    ),
    (
        "cl_aluminium",
        include_str!("../../../../assets/scenes/cl_aluminium.toml"),
    ),
    (
        "cj_iron",
        include_str!("../../../../assets/scenes/cj_iron.toml"),
    ),
    (
        "cl_iron",
        include_str!("../../../../assets/scenes/cl_iron.toml"),
    ),
    (
        "cj_light_load",
        include_str!("../../../../assets/scenes/cj_light_load.toml"),
    ),
    (
        "cl_light_load",
        include_str!("../../../../assets/scenes/cl_light_load.toml"),
    ),
    (
        "driven_cj_free_head",
        include_str!("../../../../assets/scenes/driven_cj_free_head.toml"),
    ),
    (
        "driven_cl_free_head",
        include_str!("../../../../assets/scenes/driven_cl_free_head.toml"),
    ),
    (
        "driven_cj_wall",
        include_str!("../../../../assets/scenes/driven_cj_wall.toml"),
    ),
    (
        "driven_cl_wall",
        include_str!("../../../../assets/scenes/driven_cl_wall.toml"),
    ),
    (
        "rig_driven_cj",
        include_str!("../../../../assets/scenes/rig_driven_cj.toml"),
    ),
    (
        "rig_driven_cl",
        include_str!("../../../../assets/scenes/rig_driven_cl.toml"),
    ),
];

/// Bundled scene `name` with text replacements applied (for studies that vary one setting:
/// `flexrig validate`, `flexrig bench`).
pub fn bundled_scene(name: &str, edits: &[(&str, &str)]) -> Result<Scene, Error> {
    let (mut text, _) = scene_text(name, None)?;
    for (from, to) in edits {
        text = text.replace(from, to);
    }
    Ok(Scene::from_toml_str(&text, &Materials::bundled()?)?)
}

/// The text of scene `name` and where it came from: `dir/name.toml` if `dir` is given and holds
/// that file, else the bundled copy (a directory may hold any subset of the scenes).
pub fn scene_text(name: &str, dir: Option<&Path>) -> Result<(String, String), Error> {
    if let Some(dir) = dir {
        let path = dir.join(format!("{name}.toml"));
        if std::fs::symlink_metadata(&path).is_ok() {
            let text = crate::shared::output::read_text(&path)?;
            return Ok((text, path.display().to_string()));
        }
    }
    let text = bundled_text(name).ok_or_else(|| Error::InvalidArgument {
        arg: "scene".into(),
        value: name.into(),
        allowed: format!("must be one of {}", bundled_names().join(", ")),
    })?;
    Ok((text.to_string(), format!("bundled {name}.toml")))
}

/// The text of a bundled scene, if `name` is one.
pub fn bundled_text(name: &str) -> Option<&'static str> {
    BUNDLED_SCENES
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, t)| *t)
}

/// The names of the bundled scenes, in their listing order.
pub fn bundled_names() -> Vec<&'static str> {
    BUNDLED_SCENES.iter().map(|(n, _)| *n).collect()
}

/// A bundled scene as `flexrig scenes` lists it.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct BundledScene {
    /// Its name (what `flexrig run NAME` takes).
    pub name: &'static str,
    /// The first sentence of the scene file's `description` (on one line).
    pub summary: String,
}

/// Every bundled scene with the one-line summary of its `description` field, read from the
/// scene file itself (a scene registered in [`BUNDLED_SCENES`] is listed with no other edit).
pub fn list_bundled() -> Vec<BundledScene> {
    BUNDLED_SCENES
        .iter()
        .map(|(name, text)| BundledScene {
            name,
            summary: summary(text),
        })
        .collect()
}

/// The first sentence of a scene text's `description` (its lines joined), or "" without one: the
/// text up to the first full stop followed by a capital letter (so `Fig. 9a` and `0.1 kg` do not
/// end it) or up to a colon that opens a list (`: -`), whichever comes first.
fn summary(text: &str) -> String {
    let description = toml::from_str::<toml::Table>(text)
        .ok()
        .and_then(|t| t.get("description")?.as_str().map(str::to_string))
        .unwrap_or_default();
    let words = description
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join(" ");
    let chars: Vec<(usize, char)> = words.char_indices().collect();
    for (k, &(at, c)) in chars.iter().enumerate() {
        let next = chars.get(k + 1).map(|&(_, c)| c);
        let after = chars.get(k + 2).map(|&(_, c)| c);
        if c == '.' && next == Some(' ') && after.is_some_and(char::is_uppercase) {
            return words[..=at].to_string();
        }
        if c == ':' && next == Some(' ') && after == Some('-') {
            return words[..at].to_string();
        }
    }
    words.trim_end_matches(':').to_string()
}

/// The bundled name closest to `name` (a near miss such as `cj_aluminum` or `cl-iron`): at an
/// edit distance of at most a third of its length (at least 2), case and `-`/`_` ignored.
pub fn did_you_mean(name: &str) -> Option<&'static str> {
    let key = |s: &str| s.to_lowercase().replace('-', "_");
    let given = key(name);
    let limit = (given.chars().count() / 3).max(2);
    BUNDLED_SCENES
        .iter()
        .map(|(n, _)| (edit_distance(&given, &key(n)), *n))
        .filter(|(d, _)| *d <= limit)
        .min_by_key(|(d, _)| *d)
        .map(|(_, n)| n)
}

/// Levenshtein distance (insertions, deletions, substitutions) in characters.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let above = row[j + 1];
            row[j + 1] = (above + 1)
                .min(row[j] + 1)
                .min(diagonal + usize::from(ca != *cb));
            diagonal = above;
        }
    }
    row[b.len()]
}

/// A scene as given to a command: the name of a bundled scene or the path of a scene file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SceneSource {
    /// The scene's TOML text.
    pub text: String,
    /// Where it came from, as messages say it: `bundled cj_aluminium` or the path.
    pub origin: String,
    /// The file's path (none for a bundled scene): value files of a sweep are read beside it.
    pub path: Option<PathBuf>,
}

/// Resolves `given` (what the user typed for `arg`, e.g. `SCENE`, `--scene`, `BASE`): the
/// bundled scene of that name, else the scene file at that path. A name that is neither is
/// refused naming `arg`, the bundled names and, for a near miss, the closest one
/// ([`did_you_mean`]); an unreadable file is a read error naming the file.
pub fn resolve(arg: &str, path: &Path) -> Result<SceneSource, Error> {
    let name = path.to_str();
    if let Some((given, text)) = name.and_then(|n| Some((n, bundled_text(n)?))) {
        return Ok(SceneSource {
            text: text.to_string(),
            origin: format!("bundled {given}"),
            path: None,
        });
    }
    if path.as_os_str().is_empty() {
        return Err(Error::InvalidArgument {
            arg: arg.into(),
            value: String::new(),
            allowed: format!(
                "is empty: give the name of a bundled scene ({}) or the path of a scene file",
                bundled_names().join(", ")
            ),
        });
    }
    // a bare word that is no file: a misspelt bundled name, not a missing file
    let bare_word = name.filter(|n| {
        !n.is_empty() && !n.contains(['/', '\\', '.']) && std::fs::symlink_metadata(path).is_err()
    });
    if let Some(given) = bare_word {
        let hint = did_you_mean(given)
            .map(|n| format!("did you mean {n}? "))
            .unwrap_or_default();
        return Err(Error::InvalidArgument {
            arg: arg.into(),
            value: given.into(),
            allowed: format!(
                "{hint}give the name of a bundled scene ({}; `flexrig scenes` lists them) or \
                 the path of a scene file",
                bundled_names().join(", ")
            ),
        });
    }
    if path.is_dir() {
        return Err(Error::InvalidArgument {
            arg: arg.into(),
            value: path.display().to_string(),
            allowed: "is a directory: give a scene file, or the name of a bundled scene".into(),
        });
    }
    let text = crate::shared::output::read_text(path)?;
    Ok(SceneSource {
        text,
        origin: path.display().to_string(),
        path: Some(path.to_path_buf()),
    })
}

/// Writes bundled scene `name` to `path` (to edit it); an existing file is kept unless `force`.
/// Errors name `NAME` (an unknown name, with [`did_you_mean`]) or `--out`.
pub fn write_bundled(name: &str, path: &Path, force: bool) -> Result<(), Error> {
    let Some(text) = bundled_text(name) else {
        let hint = did_you_mean(name)
            .map(|n| format!("did you mean {n}? "))
            .unwrap_or_default();
        return Err(Error::InvalidArgument {
            arg: "--write".into(),
            value: name.into(),
            allowed: format!("{hint}must be one of {}", bundled_names().join(", ")),
        });
    };
    if !force && std::fs::symlink_metadata(path).is_ok() {
        return Err(Error::InvalidArgument {
            arg: "--out".into(),
            value: path.display().to_string(),
            allowed: "exists; give another file name, or --force to overwrite it".into(),
        });
    }
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        crate::shared::output::ensure_dir(dir)?;
    }
    crate::shared::output::write_atomic(path, text.as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn near_misses_find_their_scene() {
        assert_eq!(did_you_mean("cj_aluminum"), Some("cj_aluminium"));
        assert_eq!(did_you_mean("CL-iron"), Some("cl_iron"));
        assert_eq!(did_you_mean("cl_light_lod"), Some("cl_light_load"));
        assert_eq!(did_you_mean("banana"), None);
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("", "abc"), 3);
    }

    #[test]
    fn resolve_takes_names_and_paths() {
        let by_name = resolve("SCENE", Path::new("cj_iron")).unwrap();
        assert_eq!(by_name.text, bundled_text("cj_iron").unwrap());
        assert!(by_name.path.is_none());
        let err = resolve("SCENE", Path::new("cj_aluminum"))
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("SCENE") && err.contains("did you mean cj_aluminium?"),
            "{err}"
        );
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../assets/scenes/cl_iron.toml"
        );
        let by_path = resolve("SCENE", Path::new(path)).unwrap();
        assert_eq!(by_path.text, bundled_text("cl_iron").unwrap());
        assert!(matches!(
            resolve("SCENE", Path::new("no/such/scene.toml")),
            Err(Error::Read { .. })
        ));
    }

    #[test]
    fn every_bundled_scene_has_a_one_line_summary() {
        for s in list_bundled() {
            assert!(!s.summary.is_empty() && !s.summary.contains('\n'), "{s:?}");
        }
    }

    #[test]
    fn every_bundled_summary_is_its_descriptions_first_sentence() {
        for scene in list_bundled() {
            let s = &scene.summary;
            assert!(s.ends_with('.'), "{}: {s}", scene.name);
            assert!(!s.contains("Sources and choices"), "{}: {s}", scene.name);
            assert!(
                !s.contains(". V") && !s.contains(": -"),
                "{}: {s}",
                scene.name
            );
            assert!(s.len() > 40, "{}: {s}", scene.name);
        }
        let rig = list_bundled()
            .into_iter()
            .find(|b| b.name == "rig_driven_cl")
            .unwrap();
        assert!(
            rig.summary
                .ends_with("the drive of rig_driven_cj on the compliant link."),
            "{}",
            rig.summary
        );
        let cj = list_bundled()
            .into_iter()
            .find(|b| b.name == "cj_aluminium")
            .unwrap();
        assert!(
            cj.summary
                .starts_with("Paper §VI, Fig. 9a: compliant joint"),
            "{}",
            cj.summary
        );
        assert!(cj.summary.ends_with("payload 412 g."), "{}", cj.summary);
    }
}
