//! `steadyray suite`: the subjective comparison over the scene suite (`docs/scene-suite.md`).
//! The plan, its cells, shards and table are `steadyray-suite`'s; this module runs a cell as
//! a real-clock bench of its method on its scene ([`runner`]), calibrates `perceptual`'s
//! model once per scene for the methods that need one (`perceptual-scene`), scores JOD where the JOD tool is installed, and writes the table
//! and its plot ([`table`]).

pub mod plot;
pub mod runner;
pub mod table;

pub use runner::{SuiteCommands, SuiteConfig, run};
pub use table::write_table;
