//! Scenes for this crate's unit tests.

use glam::Vec3;
use steadyray_scene::{Material, Object, Scene};

/// The corridor's camera and path with `objects` only, all of one white diffuse material.
pub(crate) fn scene_of(objects: Vec<Object>) -> Scene {
    let mut s = steadyray_scene::builtin("corridor").unwrap();
    s.materials = vec![(
        "m".into(),
        Material::Diffuse {
            albedo: Vec3::ONE,
            checker: None,
        },
    )];
    s.objects = objects;
    s
}
