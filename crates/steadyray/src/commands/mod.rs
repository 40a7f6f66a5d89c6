//! The commands the binary keeps (the experiment's are in `steadyray_experiment`).

pub mod render;
pub mod scenes;
