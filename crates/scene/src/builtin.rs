//! The built-in scenes, written in the TOML scene format (`crates/scene/builtin/*.toml`) and
//! embedded in the binary, so that every backend, test and benchmark can name them.

use crate::Scene;
use crate::error::{SceneError, SceneErrorKind};
use crate::format::parse_scene;

/// The scene used when none is named: the paper's benchmark corridor (`docs/corridor.md`).
pub const DEFAULT_SCENE: &str = "corridor";

/// A built-in scene: its name, a one-line description (for `steadyray scenes`) and its TOML.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BuiltinScene {
    /// The name `--scene` takes and the scene's `name`.
    pub name: &'static str,
    /// One line for `steadyray scenes`.
    pub description: &'static str,
    /// The scene file's text, in the TOML scene format.
    pub toml: &'static str,
}

const BUILTINS: [BuiltinScene; 4] = [
    BuiltinScene {
        name: "corridor",
        description: "the paper's benchmark: a mirror-lined corridor with coloured, glass and \
                      chrome spheres, camera sweeping a full turn (docs/corridor.md)",
        toml: include_str!("../builtin/corridor.toml"),
    },
    BuiltinScene {
        name: "cornell",
        description: "a closed Cornell box (red and green walls) with a mirror and a glass \
                      sphere, lit from under the ceiling, camera turning inside",
        toml: include_str!("../builtin/cornell.toml"),
    },
    BuiltinScene {
        name: "spheres",
        description: "a 9x9 field of diffuse, mirror and glass spheres on a checker plane \
                      under four lights, camera orbiting",
        toml: include_str!("../builtin/spheres.toml"),
    },
    BuiltinScene {
        name: "flyby",
        description: "a moving world: objects flying between two mirror walls, a swarm of 120 \
                      appearing at 4 s and gone at 8 s, a glass ball passing the camera, \
                      camera flying a closed keyed path (12 s)",
        toml: include_str!("../builtin/flyby.toml"),
    },
];

const NAMES: [&str; 4] = [
    BUILTINS[0].name,
    BUILTINS[1].name,
    BUILTINS[2].name,
    BUILTINS[3].name,
];

/// The names of the built-in scenes, default first.
pub fn builtin_names() -> &'static [&'static str] {
    &NAMES
}

/// Every built-in scene with its description and source.
pub fn builtin_scenes() -> &'static [BuiltinScene] {
    &BUILTINS
}

/// The one-line description of built-in scene `name`.
pub fn builtin_description(name: &str) -> Option<&'static str> {
    BUILTINS
        .iter()
        .find(|b| b.name == name)
        .map(|b| b.description)
}

/// The built-in scene `name`, parsed from its embedded TOML (origin `builtin/<name>.toml`).
pub fn builtin(name: &str) -> Result<Scene, SceneError> {
    match BUILTINS.iter().find(|b| b.name == name) {
        Some(b) => parse_scene(b.toml, &format!("builtin/{}.toml", b.name), None),
        None => Err(SceneError::new(
            name,
            None,
            SceneErrorKind::UnknownScene,
            format!(
                "no built-in scene of that name (built-ins: {})",
                NAMES.join(", ")
            ),
        )),
    }
}
