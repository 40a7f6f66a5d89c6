//! Where the suite keeps its cells: `DIR/cells/<scene>/<method>/run-<k>/`, each holding the
//! bench's outputs and, written last and atomically, `cell.json`, the mark of a finished
//! cell. A folder without it is a cell that was killed: it is cleared and run again.

use crate::cell::{Cell, CellResult};
use crate::error::SuiteError;
use std::fs;
use std::path::{Path, PathBuf};

/// The file that marks a finished cell and holds its result.
pub const RESULT_FILE: &str = "cell.json";

/// The cell's folder under the suite's folder `root`.
pub fn cell_dir(root: &Path, cell: &Cell) -> PathBuf {
    root.join("cells").join(cell.id())
}

/// The cell's result if it finished, None if it has not; an error for a result file that
/// cannot be read or is not the cell's.
pub fn finished(root: &Path, cell: &Cell) -> Result<Option<CellResult>, SuiteError> {
    let path = cell_dir(root, cell).join(RESULT_FILE);
    if !path.exists() {
        return Ok(None);
    }
    let result = read_result(&path)?;
    if &result.cell != cell {
        return Err(SuiteError::BadResult {
            path,
            message: format!("it is the result of {}", result.cell.id()),
        });
    }
    Ok(Some(result))
}

/// Makes the cell's folder empty (clearing what a killed run left) and returns it.
pub fn fresh_cell_dir(root: &Path, cell: &Cell) -> Result<PathBuf, SuiteError> {
    let dir = cell_dir(root, cell);
    if dir.exists() {
        fs::remove_dir_all(&dir).map_err(|e| SuiteError::io(&dir, e))?;
    }
    fs::create_dir_all(&dir).map_err(|e| SuiteError::io(&dir, e))?;
    Ok(dir)
}

/// Writes the cell's result: to a temporary file first, renamed into place, so that a
/// result file is always whole.
pub fn write_result(root: &Path, result: &CellResult) -> Result<(), SuiteError> {
    let dir = cell_dir(root, &result.cell);
    let path = dir.join(RESULT_FILE);
    let temporary = dir.join(format!("{RESULT_FILE}.partial"));
    let text = serde_json::to_string_pretty(result).expect("a cell result serialises");
    fs::write(&temporary, text).map_err(|e| SuiteError::io(&temporary, e))?;
    fs::rename(&temporary, &path).map_err(|e| SuiteError::io(&path, e))
}

/// Every finished cell's result under `root`, in the order of their folders' names.
pub fn read_all(root: &Path) -> Result<Vec<CellResult>, SuiteError> {
    let mut files = Vec::new();
    collect_results(&root.join("cells"), &mut files)?;
    files.sort();
    files.iter().map(|f| read_result(f)).collect()
}

fn collect_results(dir: &Path, files: &mut Vec<PathBuf>) -> Result<(), SuiteError> {
    if !dir.is_dir() {
        return Ok(());
    }
    for entry in fs::read_dir(dir).map_err(|e| SuiteError::io(dir, e))? {
        let path = entry.map_err(|e| SuiteError::io(dir, e))?.path();
        if path.is_dir() {
            collect_results(&path, files)?;
        } else if path.file_name().is_some_and(|n| n == RESULT_FILE) {
            files.push(path);
        }
    }
    Ok(())
}

fn read_result(path: &Path) -> Result<CellResult, SuiteError> {
    let text = fs::read_to_string(path).map_err(|e| SuiteError::io(path, e))?;
    serde_json::from_str(&text).map_err(|e| SuiteError::BadResult {
        path: path.to_path_buf(),
        message: e.to_string(),
    })
}
