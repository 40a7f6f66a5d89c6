//! The scene model of steadyray: what is drawn (shapes, materials, lights), from where
//! (camera, camera paths), and how it is written down (the TOML scene format, built-ins).
//!
//! Everything here is plain data. The renderers read it; nothing here renders.

pub mod camera;
pub mod light;
pub mod material;
pub mod path;
pub mod scene;
pub mod shape;

pub use camera::Camera;
pub use glam::Vec3;
pub use light::PointLight;
pub use material::{Checker, Material};
pub use path::CameraPath;
pub use scene::{Object, Scene};
pub use shape::{Shape, TriangleMesh};
