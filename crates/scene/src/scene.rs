//! The whole scene: objects, materials, lights, environment, camera and camera path.

use crate::{Camera, CameraPath, Material, Motion, PointLight, Shape};
use glam::Vec3;

/// A shape with a name (for messages and round-trips), an index into `Scene::materials`,
/// and how it moves.
#[derive(Clone, Debug, PartialEq)]
pub struct Object {
    /// Unique among a loaded scene's objects; messages and the writer use it.
    pub name: String,
    /// The geometry, in world space (meshes with their placement).
    pub shape: Shape,
    /// Index into `Scene::materials`.
    pub material: usize,
    /// `None`: the object never moves and always exists.
    pub motion: Option<Motion>,
}

impl Object {
    /// An object that never moves.
    pub fn fixed(name: impl Into<String>, shape: Shape, material: usize) -> Self {
        Self {
            name: name.into(),
            shape,
            material,
            motion: None,
        }
    }
}

/// A complete, validated scene, ready for any renderer.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// The scene's name (a built-in's name, or what its file gives).
    pub name: String,
    /// Named materials; objects refer to them by index.
    pub materials: Vec<(String, Material)>,
    /// The objects, in the file's order.
    pub objects: Vec<Object>,
    /// The point lights.
    pub lights: Vec<PointLight>,
    /// Ambient term, as a fraction of the albedo (`docs/shading.md`).
    pub ambient: f32,
    /// Radiance of rays that leave the scene.
    pub background: Vec3,
    /// The scene's own camera (frame 0 of its path).
    pub camera: Camera,
    /// How the camera moves in `bench` and `view`.
    pub path: CameraPath,
}

impl Scene {
    /// The material of object `i`.
    pub fn material_of(&self, object: usize) -> &Material {
        &self.materials[self.objects[object].material].1
    }

    /// The camera for frame `k` of `n` along the scene's path.
    pub fn camera_at(&self, k: u32, n: u32) -> Camera {
        self.path.camera(&self.camera, k, n)
    }

    /// The camera at scene time `t_s` seconds along the scene's path.
    pub fn camera_at_time(&self, t_s: f64) -> Camera {
        self.path.camera_at_time(&self.camera, t_s)
    }

    /// Whether any object moves, appears or disappears.
    pub fn is_animated(&self) -> bool {
        self.objects.iter().any(|o| o.motion.is_some())
    }
}
