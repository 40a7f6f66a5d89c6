//! The scene model of steadyray: what is drawn (shapes, materials, lights), from where
//! (camera, camera paths), and how it is written down (the TOML scene format of
//! `docs/scene-format.md`, built-in scenes, mesh import).
//!
//! Everything here is plain data. The renderers read it; nothing here renders.

pub mod builtin;
pub mod camera;
pub mod error;
pub mod format;
mod gltf_import;
pub mod light;
pub mod load;
pub mod material;
pub mod mesh_import;
pub mod motion;
pub mod path;
pub mod pose;
pub mod scene;
pub mod shape;
mod spline;
pub mod transform;
pub mod writer;

pub use builtin::{
    BuiltinScene, DEFAULT_SCENE, builtin, builtin_description, builtin_names, builtin_scenes,
};
pub use camera::Camera;
pub use error::{SceneError, SceneErrorKind};
pub use format::{parse_scene, parse_scene_with_notes};
pub use glam::Vec3;
pub use light::PointLight;
pub use load::{load_scene, load_scene_file, load_scene_file_with_notes};
pub use material::{Checker, Material};
pub use motion::{Motion, MotionKey};
pub use path::{CameraKey, CameraPath, KeyLook, KeyedPath, PathMotion};
pub use pose::Pose;
pub use scene::{Object, Scene};
pub use shape::{Shape, TriangleMesh};
pub use transform::Transform;
pub use writer::scene_to_toml;
