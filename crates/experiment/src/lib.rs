//! The experiment of steadyray as a library: the bench (the paper's experiment and its real
//! clock), the ladder and motion calibrations, the reports and plots, the JOD scores, the
//! ray-casting benchmark and image comparison, and the renderer's creation. It takes plain
//! configurations ([`config`] and each command's own) and knows nothing of the command line
//! or of the window, which the `steadyray` binary adds on top.

pub mod backend;
pub mod bench;
pub mod calibrate;
pub mod calibrate_motion;
pub mod compare;
pub mod config;
pub mod files;
pub mod frame_loop;
pub mod jod;
pub mod progress;
pub mod ray_dump;
pub mod raybench;
pub mod recommended;
pub mod suite;
