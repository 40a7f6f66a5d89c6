//! Reading the TOML scene format (`docs/scene-format.md`): the file's schema, and the checks
//! that turn it into a valid [`Scene`] or a [`SceneError`] naming the file, the line and the
//! problem. Nothing here panics on any input.
//!
//! Its parts: `schema` (what serde reads), `camera` (the camera and its paths), `shapes`
//! (materials, shapes, meshes and their copies), `motion` (moving objects) and `checks`
//! (the value checks every part shares); this module reads the whole scene with them.

use crate::Transform;
use crate::error::{SceneError, SceneErrorKind, line_of};
use crate::mesh_import;
use crate::{
    Camera, CameraKey, CameraPath, Checker, KeyLook, KeyedPath, Material, Motion, MotionKey,
    Object, PathMotion, PointLight, Scene, Shape,
};
use glam::Vec3;
use serde::Deserialize;
use std::collections::HashMap;
use std::fmt;
use std::ops::Range;
use std::path::Path;
use toml::Spanned;

/// Frames of a camera path when the file gives none.
pub const DEFAULT_FRAMES: u32 = 720;
/// Vertical field of view, degrees, when the file gives none.
pub const DEFAULT_VFOV_DEG: f32 = 60.0;

/// Parses a scene file's text. `origin` names the file in error messages; mesh paths are
/// relative to `base_dir` (the current directory when `None`).
pub fn parse_scene(text: &str, origin: &str, base_dir: Option<&Path>) -> Result<Scene, SceneError> {
    parse_scene_with_notes(text, origin, base_dir).map(|(scene, _)| scene)
}

/// As [`parse_scene`], also returning notes about what loading changed without failing
/// (such as degenerate mesh triangles that were dropped), one line each, for the user.
pub fn parse_scene_with_notes(
    text: &str,
    origin: &str,
    base_dir: Option<&Path>,
) -> Result<(Scene, Vec<String>), SceneError> {
    let raw: RawScene = toml::from_str(text).map_err(|e| {
        let line = e.span().map(|s| line_of(text, s.start));
        let mut message = e.message().trim_end().to_owned();
        // Quote the offending line, which names the key that toml's message leaves out.
        if let Some(quoted) = line.and_then(|l| text.lines().nth(l - 1)).map(str::trim)
            && !quoted.is_empty()
            && quoted.len() <= 100
        {
            message = format!("{message} (in `{quoted}`)");
        }
        SceneError::new(origin, line, SceneErrorKind::Syntax, message)
    })?;
    let mut cx = Cx {
        origin,
        text,
        base_dir,
        notes: Vec::new(),
    };
    let scene = cx.scene(raw)?;
    Ok((scene, cx.notes))
}

/// The optional keys of a table that are present, with where they are, so that keys which
/// do not belong to the table's `type` can be reported.
macro_rules! present_keys {
    ($raw:expr, $($field:ident),*) => {{
        let mut keys: Vec<(&'static str, Range<usize>)> = Vec::new();
        $( if let Some(v) = &$raw.$field { keys.push((stringify!($field), v.span())); } )*
        keys
    }};
}

mod camera;
mod checks;
mod motion;
mod schema;
mod shapes;

use schema::*;

/// Parsing context: the file (for messages and mesh paths) and the notes gathered so far.
struct Cx<'a> {
    origin: &'a str,
    text: &'a str,
    base_dir: Option<&'a Path>,
    notes: Vec<String>,
}

impl Cx<'_> {
    fn err(&self, span: Range<usize>, kind: SceneErrorKind, msg: String) -> SceneError {
        SceneError::new(self.origin, Some(line_of(self.text, span.start)), kind, msg)
    }

    fn invalid(&self, span: Range<usize>, msg: String) -> SceneError {
        self.err(span, SceneErrorKind::Invalid, msg)
    }

    fn scene(&mut self, raw: RawScene) -> Result<Scene, SceneError> {
        let name = match &raw.name {
            Some(n) => n.get_ref().clone(),
            None => Path::new(self.origin)
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default(),
        };
        let background = match &raw.background {
            Some(b) => self.colour("scene", "background", b)?,
            None => Vec3::ZERO,
        };
        let ambient = match &raw.ambient {
            Some(a) => self.non_negative("scene", "ambient", a)?,
            None => 0.0,
        };
        let camera = self.camera(&raw.camera)?;
        let path = match &raw.path {
            Some(p) => self.path(p)?,
            None => CameraPath::sweep(DEFAULT_FRAMES),
        };

        let mut materials = Vec::with_capacity(raw.materials.len());
        let mut material_index: HashMap<String, usize> = HashMap::new();
        for m in &raw.materials {
            let name = self.unique_name("material", &m.get_ref().name, &material_index)?;
            material_index.insert(name.to_owned(), materials.len());
            materials.push((name.to_owned(), self.material(m)?));
        }

        let mut objects = Vec::with_capacity(raw.shapes.len());
        // Shape names (also those made for the parts of glTF meshes) and the ordinal of the
        // `[[shapes]]` table that made each.
        let mut shape_names: HashMap<String, usize> = HashMap::new();
        for (ordinal, s) in raw.shapes.iter().enumerate() {
            let r = s.get_ref();
            let name = self.unique_name("shape", &r.name, &shape_names)?;
            shape_names.insert(name.to_owned(), ordinal);
            let Some(material_key) = &r.material else {
                let tables = (&mut materials, &mut material_index);
                self.file_materials_shape(
                    s,
                    (name, ordinal),
                    tables,
                    &mut shape_names,
                    &mut objects,
                )?;
                continue;
            };
            let material = match material_index.get(material_key.get_ref().as_str()) {
                Some(&i) => i,
                None => {
                    let known: Vec<&str> = materials.iter().map(|(n, _)| n.as_str()).collect();
                    return Err(self.invalid(
                        material_key.span(),
                        format!(
                            "shape {name:?}: unknown material {:?} (materials: {})",
                            material_key.get_ref(),
                            if known.is_empty() {
                                "none defined".to_owned()
                            } else {
                                known.join(", ")
                            }
                        ),
                    ));
                }
            };
            objects.push(Object {
                name: name.to_owned(),
                shape: self.shape(s, name)?,
                material,
                motion: self.shape_motion(r, name)?,
            });
        }

        let lights = raw
            .lights
            .iter()
            .enumerate()
            .map(|(i, l)| {
                let label = format!("light {}", i + 1);
                let r = l.get_ref();
                Ok(PointLight {
                    position: self.vec3(&label, "position", &r.position)?,
                    intensity: self.colour(&label, "intensity", &r.intensity)?,
                })
            })
            .collect::<Result<_, SceneError>>()?;

        Ok(Scene {
            name,
            materials,
            objects,
            lights,
            ambient,
            background,
            camera,
            path,
        })
    }

    /// A mesh read from a glTF file that gives no `material`: one object per part, each with
    /// a material made from the file's own (named `shape/material`), added to `materials`
    /// and to `objects`; the parts' names go into `shape_names` (with the `[[shapes]]`
    /// table's `ordinal`) when there are several.
    fn file_materials_shape(
        &mut self,
        s: &Spanned<RawShape>,
        (name, ordinal): (&str, usize),
        (materials, material_index): (&mut Vec<(String, Material)>, &mut HashMap<String, usize>),
        shape_names: &mut HashMap<String, usize>,
        objects: &mut Vec<Object>,
    ) -> Result<(), SceneError> {
        let r = s.get_ref();
        let gltf_file = r.kind.get_ref() == "mesh"
            && r.positions.is_none()
            && r.triangles.is_none()
            && r.path
                .as_ref()
                .is_some_and(|p| mesh_import::is_gltf_path(Path::new(p.get_ref())));
        if !gltf_file {
            return Err(self.invalid(
                s.span(),
                format!(
                    "shape {name:?}: missing `material` (only a mesh read from a glTF \
                     file, .gltf or .glb, may leave it out to use the file's own \
                     materials)"
                ),
            ));
        }
        let (file_materials, parts) = self.gltf_parts(s, name)?;
        let label = format!("shape {name:?}");
        let placement = self.mesh_transform(r, &label)?;
        let instances = self.instances(r, &label)?;
        let motion = self.shape_motion(r, name)?;
        let mut made: HashMap<usize, usize> = HashMap::new();
        let several = parts.len() > 1;
        for (mesh, m) in parts {
            let (label, material) = &file_materials[m];
            let material = match made.get(&m) {
                Some(&i) => i,
                None => {
                    let material_name = format!("{name}/{label}");
                    if material_index.contains_key(&material_name) {
                        return Err(self.invalid(
                            r.name.span(),
                            format!(
                                "shape {name:?}: the material made for glTF material \
                                 {label:?} would be named {material_name:?}, which is \
                                 already a material; rename the shape or that material"
                            ),
                        ));
                    }
                    material_index.insert(material_name.clone(), materials.len());
                    materials.push((material_name, material.clone()));
                    made.insert(m, materials.len() - 1);
                    materials.len() - 1
                }
            };
            let object_name = if several {
                format!("{name}/{label}")
            } else {
                name.to_owned()
            };
            if several {
                if let Some(first) = shape_names.get(&object_name) {
                    return Err(self.invalid(
                        r.name.span(),
                        format!(
                            "shape {name:?}: the part for glTF material {label:?} \
                             would be named {object_name:?}, which shape {} already \
                             uses",
                            first + 1
                        ),
                    ));
                }
                shape_names.insert(object_name.clone(), ordinal);
            }
            objects.push(Object {
                name: object_name,
                shape: Shape::Mesh {
                    mesh,
                    placement,
                    instances: instances.clone(),
                },
                material,
                motion: motion.clone(),
            });
        }
        Ok(())
    }

    fn unique_name<'n>(
        &self,
        what: &str,
        name: &'n Spanned<String>,
        seen: &HashMap<String, usize>,
    ) -> Result<&'n str, SceneError> {
        let n = name.get_ref().as_str();
        if n.is_empty() {
            return Err(self.invalid(name.span(), format!("{what} name must not be empty")));
        }
        if let Some(first) = seen.get(n) {
            return Err(self.invalid(
                name.span(),
                format!(
                    "duplicate {what} name {n:?} (already used by {what} {})",
                    first + 1
                ),
            ));
        }
        Ok(n)
    }
}

/// `v` scaled to unit length, but returned unchanged when it is unit already (to within
/// rounding), so that a direction written out by `scene_to_toml` reads back bit for bit.
fn unit(v: Vec3) -> Vec3 {
    if (v.length_squared() - 1.0).abs() <= 1e-6 {
        v
    } else {
        v.normalize()
    }
}

/// The camera the format means by `yaw_deg`/`pitch_deg` (see `Camera::yaw_pitch`), shared with
/// the writer so that it can tell when yaw and pitch reproduce a camera exactly.
pub(crate) fn yaw_pitch_deg_camera(
    eye: Vec3,
    yaw_deg: f32,
    pitch_deg: f32,
    up: Vec3,
    vfov_deg: f32,
) -> Camera {
    Camera {
        up,
        ..Camera::yaw_pitch(eye, yaw_deg.to_radians(), pitch_deg.to_radians(), vfov_deg)
    }
}
