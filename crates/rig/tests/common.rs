//! Shared helpers of the rig tests: the bundled scenes, edited.

use flexrig_contact::Materials;
use flexrig_rig::Scene;

/// The text of a bundled scene.
pub fn scene_text(name: &str) -> String {
    let path = format!(
        "{}/../../assets/scenes/{name}.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// A bundled scene with text replacements applied (each must match).
#[allow(dead_code)] // not every test file edits scenes
pub fn scene(name: &str, edits: &[(&str, &str)]) -> Scene {
    let mut text = scene_text(name);
    for (from, to) in edits {
        assert!(text.contains(from), "{name}: no {from:?} to replace");
        text = text.replace(from, to);
    }
    Scene::from_toml_str(&text, &Materials::bundled().unwrap()).unwrap()
}
