//! The files a controller's options name (`predictive:ladder=FILE`,
//! `perceptual:model=FILE`), read from disk: the control library reads no files itself.

use steadyray_control::OptionFiles;

/// Reads the files that controller options name from the file system.
#[derive(Clone, Copy, Debug, Default)]
pub struct DiskFiles;

impl OptionFiles for DiskFiles {
    fn read(&self, path: &str) -> Result<String, String> {
        std::fs::read_to_string(path).map_err(|e| format!("cannot read {path}: {e}"))
    }
}
