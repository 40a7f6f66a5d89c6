//! The scratch folder every integration test here writes into.

use tempfile::TempDir;

/// A fresh temporary folder for the test `name`, removed when dropped (the name only marks
/// a folder that a killed test leaves behind).
pub fn scratch(name: &str) -> TempDir {
    tempfile::Builder::new()
        .prefix(&format!("steadyray-test-{name}-"))
        .tempdir()
        .unwrap()
}
