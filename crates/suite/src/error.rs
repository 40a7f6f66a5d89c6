//! What can go wrong in the suite.

use std::path::PathBuf;
use thiserror::Error;

/// A suite error: each names what it concerns.
#[derive(Debug, Error)]
pub enum SuiteError {
    /// A shard spec that is not `I/N` with 1 ≤ I ≤ N.
    #[error("shard `{0}` is not I/N with 1 <= I <= N (e.g. 2/4)")]
    BadShard(String),
    /// A name that no scene or method of the suite has.
    #[error("unknown {kind} `{name}` (known: {known})")]
    Unknown {
        /// "scene" or "method".
        kind: &'static str,
        /// The name asked for.
        name: String,
        /// The names there are.
        known: String,
    },
    /// A plan with nothing in it.
    #[error("the plan is empty: {0}")]
    EmptyPlan(&'static str),
    /// A file or folder that could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The path.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A cell's result file that is not what the suite writes.
    #[error("{path}: not a cell result: {message}")]
    BadResult {
        /// The file.
        path: PathBuf,
        /// What is wrong with it.
        message: String,
    },
    /// A cell whose run failed.
    #[error("cell {cell}: {message}")]
    CellFailed {
        /// The cell's id.
        cell: String,
        /// The runner's message.
        message: String,
    },
    /// Results with nothing to tabulate.
    #[error("no cell results under {0}")]
    NoResults(String),
}

impl SuiteError {
    /// An I/O error on `path`.
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Self::Io {
            path: path.into(),
            source,
        }
    }
}
