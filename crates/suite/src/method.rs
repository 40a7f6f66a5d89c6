//! The methods the suite compares: each is a set of `steadyray bench` flags added to the
//! suite's common ones (scene, path, clock, duration, quality, video), so a method reads as
//! the command a user would type.

use serde::{Deserialize, Serialize};

/// The placeholder in a method's flags for the scene's calibrated `perceptual` model (the
/// runner calibrates it once per scene and caches it).
pub const MODEL_PLACEHOLDER: &str = "{motion-model}";

/// One method: a name for tables and folders, a line saying what it is, and its flags.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Method {
    /// The name tables and folders use (letters, digits, `-` and `+`).
    pub name: String,
    /// What it is, in a few words.
    pub label: String,
    /// The bench flags that make it, e.g. `["--band", "refresh", "--controllers", "predictive"]`.
    pub flags: Vec<String>,
}

impl Method {
    fn new(name: &str, label: &str, flags: &str) -> Self {
        Self {
            name: name.to_string(),
            label: label.to_string(),
            flags: flags.split_whitespace().map(str::to_string).collect(),
        }
    }

    /// Whether the method needs the scene's calibrated `perceptual` model.
    pub fn needs_motion_model(&self) -> bool {
        self.flags.iter().any(|f| f.contains(MODEL_PLACEHOLDER))
    }

    /// The flags with the model placeholder replaced by `model` (a path).
    pub fn flags_with_model(&self, model: &str) -> Vec<String> {
        self.flags
            .iter()
            .map(|f| f.replace(MODEL_PLACEHOLDER, model))
            .collect()
    }
}

/// The history and its warped refreshes.
const HISTORY: &str = "--temporal on --warp";

/// The methods that matter: `predictive` at the paper's band and at bands aligned with one
/// and two refreshes, each with and without the history and its warps; `perceptual` out of
/// the box (its shipped model), without and with the history and its warps, and with the
/// scene's calibrated model (`perceptual-scene`);
/// the paper's fixed quality S = 1, R = 16 at the paper's band; and the bench's best-looking
/// fixed quality (of nine fixed qualities, the one with the lowest displayed FLIP on the
/// cell's own span; it reports the winner alone).
pub fn standard_methods() -> Vec<Method> {
    let predictive = "--controllers predictive";
    vec![
        Method::new("paper", "predictive, [15, 20] ms", predictive),
        Method::new(
            "paper+history",
            "predictive, [15, 20] ms, history and warps",
            &format!("{predictive} {HISTORY}"),
        ),
        Method::new(
            "refresh",
            "predictive, a frame every refresh",
            &format!("{predictive} --band refresh"),
        ),
        Method::new(
            "refresh+history",
            "predictive, a frame every refresh, history and warps",
            &format!("{predictive} --band refresh {HISTORY}"),
        ),
        Method::new(
            "refresh2",
            "predictive, a frame every two refreshes",
            &format!("{predictive} --band refresh:2"),
        ),
        Method::new(
            "refresh2+history",
            "predictive, a frame every two refreshes, history and warps",
            &format!("{predictive} --band refresh:2 {HISTORY}"),
        ),
        Method::new(
            "perceptual",
            "perceptual out of the box, its shipped model",
            "--controllers perceptual",
        ),
        Method::new(
            "perceptual+history",
            "perceptual out of the box, history and warps",
            &format!("--controllers perceptual {HISTORY}"),
        ),
        Method::new(
            "perceptual-scene",
            "perceptual, the scene's calibrated model",
            &format!("--controllers perceptual:model={MODEL_PLACEHOLDER}"),
        ),
        Method::new(
            "fixed-s1-r16",
            "fixed S = 1, R = 16 (the paper's baseline), [15, 20] ms",
            "--controllers fixed:spp=1;depth=16 --no-in-band-fixed --no-best-looking-fixed",
        ),
        Method::new(
            "best-looking-fixed",
            "the fixed quality with the lowest displayed FLIP of nine, [15, 20] ms",
            "--only-best-looking-fixed",
        ),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_fit_a_folder() {
        let methods = standard_methods();
        for (i, m) in methods.iter().enumerate() {
            assert!(
                m.name
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '+'),
                "{}",
                m.name
            );
            assert!(methods[..i].iter().all(|o| o.name != m.name));
        }
    }

    /// Every method makes the one run a cell scores: the fixed methods skip the bench's
    /// fixed baselines, or run one alone.
    #[test]
    fn fixed_methods_make_one_run() {
        let methods = standard_methods();
        let flags = |name: &str| &methods.iter().find(|m| m.name == name).unwrap().flags;
        let fixed = flags("fixed-s1-r16");
        assert!(fixed.contains(&"--no-in-band-fixed".to_string()));
        assert!(fixed.contains(&"--no-best-looking-fixed".to_string()));
        assert_eq!(flags("best-looking-fixed"), &["--only-best-looking-fixed"]);
    }

    #[test]
    fn only_perceptual_scene_needs_a_model_and_gets_it() {
        let methods = standard_methods();
        let needing: Vec<&str> = methods
            .iter()
            .filter(|m| m.needs_motion_model())
            .map(|m| m.name.as_str())
            .collect();
        assert_eq!(needing, ["perceptual-scene"]);
        let p = methods.iter().find(|m| m.name == needing[0]).unwrap();
        assert_eq!(
            p.flags_with_model("models/glass/motion.json"),
            ["--controllers", "perceptual:model=models/glass/motion.json"]
        );
        let shipped = methods.iter().find(|m| m.name == "perceptual").unwrap();
        assert_eq!(shipped.flags, ["--controllers", "perceptual"]);
    }
}
