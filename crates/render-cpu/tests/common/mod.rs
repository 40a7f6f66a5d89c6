//! Scene builders shared by the integration tests (scenes are built as structs, never
//! loaded from files).

#![allow(dead_code)] // each test binary uses its own subset

use steadyray_render::{Image, RenderSettings, Renderer};
use steadyray_render_cpu::CpuRenderer;
use steadyray_scene::{Camera, CameraPath, Material, Object, PointLight, Scene, Shape, Vec3};

/// A scene of `objects` (shape, material index) with a camera at the origin looking along -z.
pub fn scene(
    materials: Vec<Material>,
    objects: Vec<(Shape, usize)>,
    lights: Vec<PointLight>,
    ambient: f32,
    background: Vec3,
) -> Scene {
    Scene {
        name: "test".into(),
        materials: materials
            .into_iter()
            .enumerate()
            .map(|(i, m)| (format!("m{i}"), m))
            .collect(),
        objects: objects
            .into_iter()
            .enumerate()
            .map(|(i, (shape, material))| Object {
                name: format!("o{i}"),
                shape,
                material,
                motion: None,
            })
            .collect(),
        lights,
        ambient,
        background,
        camera: looking_down_neg_z(),
        path: CameraPath::sweep(1),
    }
}

/// Eye at the origin, looking along -z, 60° vertical field of view.
pub fn looking_down_neg_z() -> Camera {
    Camera::look_at(Vec3::ZERO, Vec3::NEG_Z, Vec3::Y, 60.0)
}

pub fn diffuse(albedo: Vec3) -> Material {
    Material::Diffuse {
        albedo,
        checker: None,
    }
}

pub fn mirror(reflectance: Vec3) -> Material {
    Material::Mirror { reflectance }
}

pub fn glass(ior: f32) -> Material {
    Material::Dielectric {
        ior,
        tint: Vec3::ONE,
    }
}

pub fn light(position: Vec3, intensity: f32) -> PointLight {
    PointLight {
        position,
        intensity: Vec3::splat(intensity),
    }
}

pub fn sphere(center: Vec3, radius: f32) -> Shape {
    Shape::Sphere { center, radius }
}

pub fn plane(point: Vec3, normal: Vec3) -> Shape {
    Shape::Plane { point, normal }
}

pub fn settings(width: u32, height: u32, spp: f32, max_depth: u32) -> RenderSettings {
    RenderSettings {
        width,
        height,
        spp,
        max_depth,
    }
}

/// A renderer with `scene` loaded.
pub fn loaded(scene: &Scene) -> CpuRenderer {
    let mut r = CpuRenderer::with_threads(2);
    r.load_scene(scene).expect("scene loads");
    r
}

/// Renders `scene` from its camera and returns the image.
pub fn render(scene: &Scene, s: RenderSettings) -> Image {
    let mut r = loaded(scene);
    r.render(&scene.camera, 0.0, &s).expect("renders");
    r.read_image().expect("image")
}

pub fn v(p: [f32; 3]) -> Vec3 {
    Vec3::from(p)
}

pub fn assert_close(got: Vec3, want: Vec3, tol: f32, what: &str) {
    assert!(
        (got - want).abs().max_element() <= tol,
        "{what}: got {got}, want {want}"
    );
}

/// A scene like the benchmark corridor of `docs/corridor.md` (two mirror walls, a checker
/// floor, diffuse, glass and chrome spheres, three lights).
pub fn corridor() -> Scene {
    let grey = |g: f32| Vec3::splat(g);
    let materials = vec![
        mirror(grey(0.9)),
        Material::Diffuse {
            albedo: grey(0.8),
            checker: Some(steadyray_scene::Checker {
                size: 0.5,
                albedo_b: grey(0.25),
            }),
        },
        diffuse(v([0.8, 0.15, 0.1])),
        diffuse(v([0.15, 0.7, 0.2])),
        diffuse(v([0.15, 0.3, 0.85])),
        glass(1.5),
        mirror(grey(0.95)),
        diffuse(v([0.9, 0.8, 0.2])),
        diffuse(grey(0.7)),
        diffuse(v([0.6, 0.4, 0.7])),
        diffuse(v([0.4, 0.6, 0.8])),
    ];
    let wall = |x: f32| Shape::Quad {
        corner: v([x, 0.0, -12.0]),
        edge_u: v([0.0, 3.0, 0.0]),
        edge_v: v([0.0, 0.0, 10.0]),
    };
    let objects = vec![
        (wall(-2.0), 0),
        (wall(2.0), 0),
        (
            Shape::Quad {
                corner: v([-2.0, 0.0, -12.0]),
                edge_u: v([4.0, 0.0, 0.0]),
                edge_v: v([0.0, 0.0, 10.0]),
            },
            1,
        ),
        (sphere(v([-0.8, 0.5, -5.0]), 0.5), 2),
        (sphere(v([0.9, 0.6, -7.0]), 0.6), 3),
        (sphere(v([0.0, 0.7, -9.5]), 0.7), 4),
        (sphere(v([0.6, 0.45, -4.0]), 0.45), 5),
        (sphere(v([-1.0, 0.55, -8.0]), 0.55), 6),
        (sphere(v([1.2, 0.35, -10.5]), 0.35), 7),
        (sphere(v([-1.5, 1.0, 6.0]), 1.0), 8),
        (sphere(v([1.5, 0.8, 7.0]), 0.8), 9),
        (sphere(v([0.0, 0.6, 5.0]), 0.6), 10),
    ];
    let lights = vec![
        light(v([0.0, 2.8, -5.0]), 6.0),
        light(v([0.0, 2.8, -9.0]), 6.0),
        light(v([0.0, 3.0, 6.0]), 6.0),
    ];
    let mut s = scene(materials, objects, lights, 0.05, v([0.05, 0.07, 0.12]));
    s.camera = Camera::yaw_pitch(v([0.0, 1.5, 0.0]), 0.0, 0.0, 60.0);
    s
}
