//! Running the cells of a plan (or of one shard of it), skipping those already finished.

use crate::cell::{Cell, CellResult};
use crate::error::SuiteError;
use crate::plan::Plan;
use crate::shard::Shard;
use crate::store;
use std::path::Path;
use std::time::Instant;

/// Runs one cell: the caller's way of running a method on a scene.
pub trait CellRunner {
    /// Runs `cell` of `plan`, writing its outputs into `dir` (an empty folder of its own),
    /// and returns what it measured (the suite adds the cell's time), or why it failed.
    fn run(&mut self, plan: &Plan, cell: &Cell, dir: &Path) -> Result<CellResult, String>;
}

/// What happened to a cell, as the progress callback hears it.
#[derive(Clone, Debug, PartialEq)]
pub enum CellEvent {
    /// It had finished before: not run again.
    AlreadyDone,
    /// It is about to run.
    Starting,
    /// It ran, taking this many seconds.
    Done(f64),
}

/// What a call of [`run_cells`] did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RunReport {
    /// The cells it ran.
    pub ran: Vec<Cell>,
    /// Cells of its slice finished before it started.
    pub already_done: usize,
    /// Seconds it spent running cells.
    pub seconds: f64,
}

/// Runs the cells of `plan` that `shard` takes and that have not finished under `root`, in
/// the plan's order, telling `progress` about each (with its position among the slice's
/// cells and their number). A cell that fails stops the run with its error; the cells
/// finished so far are kept, so the next call resumes after them.
pub fn run_cells(
    plan: &Plan,
    shard: Shard,
    root: &Path,
    runner: &mut dyn CellRunner,
    progress: &mut dyn FnMut(&Cell, usize, usize, &CellEvent),
) -> Result<RunReport, SuiteError> {
    let mine: Vec<Cell> = plan
        .cells()
        .into_iter()
        .enumerate()
        .filter(|(position, _)| shard.takes(*position))
        .map(|(_, cell)| cell)
        .collect();
    let mut report = RunReport::default();
    for (i, cell) in mine.iter().enumerate() {
        if store::finished(root, cell)?.is_some() {
            report.already_done += 1;
            progress(cell, i, mine.len(), &CellEvent::AlreadyDone);
            continue;
        }
        progress(cell, i, mine.len(), &CellEvent::Starting);
        let dir = store::fresh_cell_dir(root, cell)?;
        let start = Instant::now();
        let mut result =
            runner
                .run(plan, cell, &dir)
                .map_err(|message| SuiteError::CellFailed {
                    cell: cell.id(),
                    message,
                })?;
        result.seconds = start.elapsed().as_secs_f64();
        if &result.cell != cell {
            return Err(SuiteError::CellFailed {
                cell: cell.id(),
                message: format!("the runner returned the result of {}", result.cell.id()),
            });
        }
        store::write_result(root, &result)?;
        report.seconds += result.seconds;
        progress(cell, i, mine.len(), &CellEvent::Done(result.seconds));
        report.ran.push(cell.clone());
    }
    Ok(report)
}
