//! The scene suite: the subjective comparison over scenes of different character.
//!
//! A [`Plan`] crosses the suite's scenes ([`scene::standard_scenes`]) with the methods that
//! matter ([`method::standard_methods`]: the paper's band, one and two refreshes a frame,
//! each with and without the temporal history and its warps, `perceptual` out of the box and
//! with the scene's calibrated model, the paper's fixed quality, the best-looking fixed
//! quality) and K runs of each. Every combination is a [`Cell`]: an independent job whose
//! results are kept in its own folder ([`store`]), so a killed run resumes where it stopped
//! (finished cells are not redone) and [`Shard`]s split the cells over machines. [`table`]
//! joins the cells' results into one table: each method's score per scene (median and range
//! over the runs), its rank per scene and its mean rank.
//!
//! How a cell runs is the caller's: [`run::CellRunner`] (the `steadyray suite` command runs
//! the bench on the real clock with video and displayed quality, and scores JOD where
//! ColorVideoVDP is installed).

pub mod cell;
pub mod error;
pub mod method;
pub mod plan;
pub mod run;
pub mod scene;
pub mod shard;
pub mod store;
pub mod table;

pub use cell::{Cell, CellResult};
pub use error::SuiteError;
pub use method::Method;
pub use plan::Plan;
pub use run::{CellRunner, RunReport, run_cells};
pub use scene::SuiteScene;
pub use shard::Shard;
pub use table::{Metric, Table};
