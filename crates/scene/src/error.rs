//! The one error type of scene loading: where (file and line) and what went wrong, in words a
//! person can act on, e.g. `corridor.toml:12: shape "red": radius must be positive, got -0.5`.

use std::fmt;

/// The broad class of a [`SceneError`], for callers that react differently to, say, a file
/// that cannot be read and a scene that is malformed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SceneErrorKind {
    /// The scene file could not be read.
    Io,
    /// The text is not TOML, or a value has the wrong type, or a key is missing or unknown.
    Syntax,
    /// The TOML is well formed but describes an impossible scene (a negative radius, an
    /// unknown material name, a field of view of 200°, ...).
    Invalid,
    /// A mesh file named by the scene is missing or malformed.
    Mesh,
    /// A name given to `load_scene` is neither a built-in scene nor an existing file.
    UnknownScene,
}

/// Why a scene could not be loaded. `Display` gives `origin:line: message` (or
/// `origin: message` when no line applies), so messages point at the offending spot.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneError {
    /// The scene file's name as given by the caller (a path, or `builtin/<name>.toml`).
    pub origin: String,
    /// 1-based line in the scene file, where the problem has one.
    pub line: Option<usize>,
    /// The class of problem, for callers that react to it (the message says it for people).
    pub kind: SceneErrorKind,
    /// What is wrong, naming the object concerned (`shape "red": ...`).
    pub message: String,
}

impl SceneError {
    /// An error at an optional line of `origin`.
    pub fn new(
        origin: impl Into<String>,
        line: Option<usize>,
        kind: SceneErrorKind,
        message: impl Into<String>,
    ) -> Self {
        Self {
            origin: origin.into(),
            line,
            kind,
            message: message.into(),
        }
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(line) => write!(f, "{}:{}: {}", self.origin, line, self.message),
            None => write!(f, "{}: {}", self.origin, self.message),
        }
    }
}

impl std::error::Error for SceneError {}

/// The 1-based line of byte `offset` in `text` (offsets past the end give the last line).
pub(crate) fn line_of(text: &str, offset: usize) -> usize {
    let end = offset.min(text.len());
    text.as_bytes()[..end]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_with_and_without_line() {
        let e = SceneError::new(
            "corridor.toml",
            Some(12),
            SceneErrorKind::Invalid,
            "shape \"red\": radius must be positive, got -0.5",
        );
        assert_eq!(
            e.to_string(),
            "corridor.toml:12: shape \"red\": radius must be positive, got -0.5"
        );
        let e = SceneError::new("x.toml", None, SceneErrorKind::Io, "cannot read");
        assert_eq!(e.to_string(), "x.toml: cannot read");
    }

    #[test]
    fn line_numbers() {
        let t = "a\nb\nc";
        assert_eq!(line_of(t, 0), 1);
        assert_eq!(line_of(t, 2), 2);
        assert_eq!(line_of(t, 4), 3);
        assert_eq!(line_of(t, 100), 3);
    }
}
