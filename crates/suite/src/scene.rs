//! The suite's scenes: six of different character, each on a path whose speed on screen
//! varies (holds, slow pans, fast turns). `docs/scene-suite.md` describes them.

use serde::{Deserialize, Serialize};

/// One scene of the suite, as the bench loads it.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct SuiteScene {
    /// The name tables and folders use.
    pub name: String,
    /// A built-in scene's name or a scene file, relative to the repository.
    pub scene: String,
    /// The camera path that replaces the scene's own (`pans`), or None to keep it.
    pub path: Option<String>,
}

impl SuiteScene {
    fn new(name: &str, scene: &str, path: Option<&str>) -> Self {
        Self {
            name: name.to_string(),
            scene: scene.to_string(),
            path: path.map(str::to_string),
        }
    }
}

/// The six scenes, all on the `pans` path: the corridor, `flyby` (its world moves and its
/// load jumps) and the four files of `scenes/suite/` (glass, meshes, open, kaleidoscope).
pub fn standard_scenes() -> Vec<SuiteScene> {
    vec![
        SuiteScene::new("corridor", "corridor", Some("pans")),
        SuiteScene::new("flyby", "flyby", Some("pans")),
        SuiteScene::new("glass", "scenes/suite/glass.toml", None),
        SuiteScene::new("meshes", "scenes/suite/meshes.toml", None),
        SuiteScene::new("open", "scenes/suite/open.toml", None),
        SuiteScene::new("kaleidoscope", "scenes/suite/kaleidoscope.toml", None),
    ]
}
