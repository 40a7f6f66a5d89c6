//! One module per subcommand (`bench` has a folder of its own: `crate::bench`).

pub mod calibrate;
pub mod calibrate_motion;
pub mod compare;
pub mod jod;
pub mod ray_dump;
pub mod raybench;
pub mod render;
pub mod scenes;
