//! Loading scenes by file path or by name: the entry points the command line uses.

use crate::Scene;
use crate::builtin::{builtin, builtin_names};
use crate::error::{SceneError, SceneErrorKind};
use crate::format::parse_scene_with_notes;
use std::path::Path;

/// Reads and parses the scene file at `path`; mesh paths in it are relative to its directory.
pub fn load_scene_file(path: &Path) -> Result<Scene, SceneError> {
    load_scene_file_with_notes(path).map(|(scene, _)| scene)
}

/// As [`load_scene_file`], also returning notes on what loading changed without failing
/// (see [`crate::parse_scene_with_notes`]).
pub fn load_scene_file_with_notes(path: &Path) -> Result<(Scene, Vec<String>), SceneError> {
    let origin = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| {
        SceneError::new(
            &origin,
            None,
            SceneErrorKind::Io,
            format!("cannot read scene file: {e}"),
        )
    })?;
    parse_scene_with_notes(&text, &origin, path.parent())
}

/// A built-in scene by name (`corridor`, ...) or else a scene file by path.
pub fn load_scene(name_or_path: &str) -> Result<Scene, SceneError> {
    if builtin_names().contains(&name_or_path) {
        return builtin(name_or_path);
    }
    let path = Path::new(name_or_path);
    if path.exists() {
        return load_scene_file(path);
    }
    Err(SceneError::new(
        name_or_path,
        None,
        SceneErrorKind::UnknownScene,
        format!(
            "no such scene: not a built-in ({}) and no file at that path",
            builtin_names().join(", ")
        ),
    ))
}
