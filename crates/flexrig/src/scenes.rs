//! The bundled scenes (compiled in: the library and the binary need no assets directory) and
//! scene texts by name.

use std::path::Path;

use flexrig_contact::Materials;
use flexrig_rig::Scene;

use crate::Error;

/// The bundled scene files, compiled in (the binary needs no assets directory).
pub const BUNDLED_SCENES: [(&str, &str); 6] = [
    (
        "cj_aluminium",
        include_str!("../../../assets/scenes/cj_aluminium.toml"),
    ),
    (
        "cl_aluminium",
        include_str!("../../../assets/scenes/cl_aluminium.toml"),
    ),
    (
        "cj_iron",
        include_str!("../../../assets/scenes/cj_iron.toml"),
    ),
    (
        "cl_iron",
        include_str!("../../../assets/scenes/cl_iron.toml"),
    ),
    (
        "cj_light_load",
        include_str!("../../../assets/scenes/cj_light_load.toml"),
    ),
    (
        "cl_light_load",
        include_str!("../../../assets/scenes/cl_light_load.toml"),
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

/// The text of scene `name` and where it came from: `dir/name.toml` if `dir` is given, else the
/// bundled copy (which must exist).
pub fn scene_text(name: &str, dir: Option<&Path>) -> Result<(String, String), Error> {
    match dir {
        Some(dir) => {
            let path = dir.join(format!("{name}.toml"));
            let text = crate::output::read_text(&path)?;
            Ok((text, path.display().to_string()))
        }
        None => {
            let text = BUNDLED_SCENES
                .iter()
                .find(|(n, _)| *n == name)
                .map(|(_, t)| t.to_string())
                .expect("every experiment scene is bundled");
            Ok((text, format!("bundled {name}.toml")))
        }
    }
}
