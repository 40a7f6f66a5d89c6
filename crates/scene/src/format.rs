//! Reading the TOML scene format (`docs/scene-format.md`): the file's schema, and the checks
//! that turn it into a valid [`Scene`] or a [`SceneError`] naming the file, the line and the
//! problem. Nothing here panics on any input.

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

/// Three numbers, or one number meaning all three (grey colours, uniform scale).
#[derive(Clone, Copy, Debug)]
struct Triple([f32; 3]);

impl<'de> Deserialize<'de> for Triple {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> serde::de::Visitor<'de> for V {
            type Value = Triple;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a number or an array of three numbers")
            }
            fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<Triple, E> {
                Ok(Triple([v as f32; 3]))
            }
            fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<Triple, E> {
                Ok(Triple([v as f32; 3]))
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<Triple, E> {
                Ok(Triple([v as f32; 3]))
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(self, seq: A) -> Result<Triple, A::Error> {
                <[f32; 3]>::deserialize(serde::de::value::SeqAccessDeserializer::new(seq))
                    .map(Triple)
            }
        }
        d.deserialize_any(V)
    }
}

type V3 = [f32; 3];

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    name: Option<Spanned<String>>,
    background: Option<Spanned<Triple>>,
    ambient: Option<Spanned<f32>>,
    camera: Spanned<RawCamera>,
    path: Option<Spanned<RawPath>>,
    #[serde(default)]
    materials: Vec<Spanned<RawMaterial>>,
    #[serde(default)]
    shapes: Vec<Spanned<RawShape>>,
    #[serde(default)]
    lights: Vec<Spanned<RawLight>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCamera {
    eye: Spanned<V3>,
    target: Option<Spanned<V3>>,
    forward: Option<Spanned<V3>>,
    yaw_deg: Option<Spanned<f32>>,
    pitch_deg: Option<Spanned<f32>>,
    up: Option<Spanned<V3>>,
    vfov_deg: Option<Spanned<f32>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPath {
    #[serde(rename = "type")]
    kind: Spanned<String>,
    frames: Option<Spanned<u32>>,
    duration_s: Option<Spanned<f64>>,
    center: Option<Spanned<V3>>,
    radius: Option<Spanned<f32>>,
    height: Option<Spanned<f32>>,
    #[serde(rename = "loop")]
    looped: Option<Spanned<bool>>,
    keys: Option<Spanned<Vec<Spanned<RawCameraKey>>>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCameraKey {
    t: Spanned<f64>,
    eye: Spanned<V3>,
    target: Option<Spanned<V3>>,
    yaw_deg: Option<Spanned<f32>>,
    pitch_deg: Option<Spanned<f32>>,
    vfov_deg: Option<Spanned<f32>>,
}

/// A mesh instance's transform.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTransform {
    translate: Option<Spanned<V3>>,
    rotate_y_deg: Option<Spanned<f32>>,
    scale: Option<Spanned<Triple>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMotion {
    keys: Option<Spanned<Vec<Spanned<RawMotionKey>>>>,
    #[serde(rename = "loop")]
    looped: Option<Spanned<bool>>,
    spin_deg_per_s: Option<Spanned<f32>>,
    visible: Option<Spanned<Vec<Spanned<[f64; 2]>>>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMotionKey {
    t: Spanned<f64>,
    translate: Option<Spanned<V3>>,
    rotate_y_deg: Option<Spanned<f32>>,
    scale: Option<Spanned<Triple>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMaterial {
    name: Spanned<String>,
    #[serde(rename = "type")]
    kind: Spanned<String>,
    albedo: Option<Spanned<Triple>>,
    checker: Option<Spanned<RawChecker>>,
    reflectance: Option<Spanned<Triple>>,
    ior: Option<Spanned<f32>>,
    tint: Option<Spanned<Triple>>,
    radiance: Option<Spanned<Triple>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawChecker {
    size: Spanned<f32>,
    albedo_b: Spanned<Triple>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawShape {
    name: Spanned<String>,
    #[serde(rename = "type")]
    kind: Spanned<String>,
    material: Option<Spanned<String>>,
    center: Option<Spanned<V3>>,
    radius: Option<Spanned<f32>>,
    corner: Option<Spanned<V3>>,
    edge_u: Option<Spanned<V3>>,
    edge_v: Option<Spanned<V3>>,
    point: Option<Spanned<V3>>,
    normal: Option<Spanned<V3>>,
    path: Option<Spanned<String>>,
    positions: Option<Spanned<Vec<V3>>>,
    triangles: Option<Spanned<Vec<[u32; 3]>>>,
    translate: Option<Spanned<V3>>,
    scale: Option<Spanned<Triple>>,
    rotate_y_deg: Option<Spanned<f32>>,
    instances: Option<Spanned<Vec<Spanned<RawTransform>>>>,
    motion: Option<Spanned<RawMotion>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLight {
    position: Spanned<V3>,
    intensity: Spanned<Triple>,
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

impl RawShape {
    /// The optional keys this shape entry sets, with their spans, for the per-type checks.
    fn present_keys(&self) -> Vec<(&'static str, Range<usize>)> {
        present_keys!(
            self,
            center,
            radius,
            corner,
            edge_u,
            edge_v,
            point,
            normal,
            path,
            positions,
            triangles,
            translate,
            scale,
            rotate_y_deg,
            instances
        )
    }
}

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

    fn camera(&self, raw: &Spanned<RawCamera>) -> Result<Camera, SceneError> {
        let r = raw.get_ref();
        let label = "camera";
        let eye = self.vec3(label, "eye", &r.eye)?;
        let up = match &r.up {
            Some(u) => self.nonzero(label, "up", u)?,
            None => Vec3::Y,
        };
        let vfov_deg = match &r.vfov_deg {
            Some(v) => self.field_of_view(label, v)?,
            None => DEFAULT_VFOV_DEG,
        };
        if r.pitch_deg.is_some() && r.yaw_deg.is_none() {
            let span = r.pitch_deg.as_ref().map_or(raw.span(), |p| p.span());
            return Err(self.invalid(span, "camera: pitch_deg needs yaw_deg".to_owned()));
        }
        let given = [
            r.target.as_ref().map(|t| ("target", t.span())),
            r.forward.as_ref().map(|f| ("forward", f.span())),
            r.yaw_deg.as_ref().map(|y| ("yaw_deg", y.span())),
        ];
        let mut given: Vec<_> = given.into_iter().flatten().collect();
        given.sort_by_key(|g| g.1.start);
        if given.len() != 1 {
            let span = given.get(1).map_or(raw.span(), |g| g.1.clone());
            return Err(self.invalid(
                span,
                format!(
                    "camera: give exactly one of `target`, `forward` or `yaw_deg` (got {})",
                    if given.is_empty() {
                        "none".to_owned()
                    } else {
                        given.iter().map(|g| g.0).collect::<Vec<_>>().join(", ")
                    }
                ),
            ));
        }
        let camera = if let Some(t) = &r.target {
            let target = self.vec3(label, "target", t)?;
            if target == eye {
                return Err(
                    self.invalid(t.span(), "camera: target must differ from eye".to_owned())
                );
            }
            Camera::look_at(eye, target, up, vfov_deg)
        } else if let Some(f) = &r.forward {
            Camera {
                eye,
                forward: unit(self.nonzero(label, "forward", f)?),
                up,
                vfov_deg,
            }
        } else {
            let yaw = r
                .yaw_deg
                .as_ref()
                .map_or(Ok(0.0), |y| self.number(label, "yaw_deg", y))?;
            let pitch = r
                .pitch_deg
                .as_ref()
                .map_or(Ok(0.0), |p| self.number(label, "pitch_deg", p))?;
            yaw_pitch_deg_camera(eye, yaw, pitch, up, vfov_deg)
        };
        // A view along `up` is allowed: `Camera::frame` picks another `right` axis for it.
        Ok(camera)
    }

    fn path(&self, raw: &Spanned<RawPath>) -> Result<CameraPath, SceneError> {
        let r = raw.get_ref();
        let label = "path";
        let frames = match &r.frames {
            Some(f) if *f.get_ref() == 0 => {
                return Err(self.invalid(f.span(), "path: frames must be at least 1, got 0".into()));
            }
            Some(f) => *f.get_ref(),
            None => DEFAULT_FRAMES,
        };
        let duration_s = match &r.duration_s {
            Some(d) => Some(self.positive_seconds(label, "duration_s", d)?),
            None => None,
        };
        let mut keys = present_keys!(r, center, radius, height, keys);
        if let Some(l) = &r.looped {
            keys.push(("loop", l.span()));
        }
        let motion = match r.kind.get_ref().as_str() {
            "sweep" => {
                self.only_keys(label, "a sweep path", &keys, &[])?;
                PathMotion::Sweep
            }
            "orbit" => {
                self.only_keys(
                    label,
                    "an orbit path",
                    &keys,
                    &["center", "radius", "height"],
                )?;
                let center = self.vec3(
                    label,
                    "center",
                    self.required(label, "center", &r.center, raw)?,
                )?;
                let radius = self.positive(
                    label,
                    "radius",
                    self.required(label, "radius", &r.radius, raw)?,
                )?;
                let height = match &r.height {
                    Some(h) => self.number(label, "height", h)?,
                    None => 0.0,
                };
                PathMotion::Orbit {
                    center,
                    radius,
                    height,
                }
            }
            "pans" => {
                self.only_keys(label, "a pans path", &keys, &[])?;
                PathMotion::Pans
            }
            "keys" => {
                self.only_keys(label, "a keys path", &keys, &["keys", "loop"])?;
                let path = self.keyed_path(raw, frames, duration_s)?;
                PathMotion::Keys(path)
            }
            other => {
                return Err(self.invalid(
                    r.kind.span(),
                    format!(
                        "path: unknown path type {other:?} (expected \"sweep\", \"orbit\", \"pans\" or \"keys\")"
                    ),
                ));
            }
        };
        Ok(CameraPath {
            motion,
            frames,
            duration_s,
        })
    }

    /// The keys of a `type = "keys"` path: at least two, from t = 0, strictly increasing, all
    /// looking the same way; looped, all before the path's end.
    fn keyed_path(
        &self,
        raw: &Spanned<RawPath>,
        frames: u32,
        duration_s: Option<f64>,
    ) -> Result<KeyedPath, SceneError> {
        let r = raw.get_ref();
        let raw_keys = self.required("path", "keys", &r.keys, raw)?;
        if raw_keys.get_ref().len() < 2 {
            return Err(self.invalid(
                raw_keys.span(),
                format!(
                    "path: a keys path needs at least two keys, got {}",
                    raw_keys.get_ref().len()
                ),
            ));
        }
        let mut keys: Vec<CameraKey> = Vec::with_capacity(raw_keys.get_ref().len());
        for (i, k) in raw_keys.get_ref().iter().enumerate() {
            let label = &format!("path: key {}", i + 1);
            let kr = k.get_ref();
            let t = self.seconds(label, "t", &kr.t)?;
            match keys.last() {
                None if t != 0.0 => {
                    return Err(self.invalid(
                        kr.t.span(),
                        format!("{label}: the first key must be at t = 0, got {t}"),
                    ));
                }
                Some(prev) if t <= prev.t => {
                    return Err(self.invalid(
                        kr.t.span(),
                        format!(
                            "{label}: key times must increase, but t = {t} is not after key \
                             {}'s t = {}",
                            i, prev.t
                        ),
                    ));
                }
                _ => {}
            }
            let eye = self.vec3(label, "eye", &kr.eye)?;
            if kr.pitch_deg.is_some() && kr.yaw_deg.is_none() {
                let span = kr.pitch_deg.as_ref().map_or(k.span(), |p| p.span());
                return Err(self.invalid(span, format!("{label}: pitch_deg needs yaw_deg")));
            }
            let look = match (&kr.target, &kr.yaw_deg) {
                (Some(t), None) => {
                    let target = self.vec3(label, "target", t)?;
                    if target == eye {
                        return Err(
                            self.invalid(t.span(), format!("{label}: target must differ from eye"))
                        );
                    }
                    KeyLook::Target(target)
                }
                (None, Some(y)) => KeyLook::YawPitch {
                    yaw_deg: self.number(label, "yaw_deg", y)?,
                    pitch_deg: match &kr.pitch_deg {
                        Some(p) => self.number(label, "pitch_deg", p)?,
                        None => 0.0,
                    },
                },
                (Some(_), Some(y)) => {
                    return Err(self.invalid(
                        y.span(),
                        format!("{label}: give `target` or `yaw_deg`, not both"),
                    ));
                }
                (None, None) => {
                    return Err(self.invalid(
                        k.span(),
                        format!("{label}: give `target` or `yaw_deg` (and `pitch_deg`)"),
                    ));
                }
            };
            if let Some(first) = keys.first()
                && matches!(first.look, KeyLook::Target(_)) != matches!(look, KeyLook::Target(_))
            {
                return Err(self.invalid(
                    k.span(),
                    format!(
                        "{label}: every key must look the same way, all with `target` or all \
                         with `yaw_deg`/`pitch_deg`, but key 1 uses {}",
                        if matches!(first.look, KeyLook::Target(_)) {
                            "`target`"
                        } else {
                            "`yaw_deg`"
                        }
                    ),
                ));
            }
            let vfov_deg = match &kr.vfov_deg {
                Some(v) => Some(self.field_of_view(label, v)?),
                None => None,
            };
            keys.push(CameraKey {
                t,
                eye,
                look,
                vfov_deg,
            });
        }
        let looped = r.looped.as_ref().is_some_and(|l| *l.get_ref());
        let duration = duration_s.unwrap_or(frames as f64 / 60.0);
        let last = keys[keys.len() - 1].t;
        if looped && last >= duration {
            return Err(self.invalid(
                raw_keys.span(),
                format!(
                    "path: a looped keys path runs from its last key back to its first by the \
                     path's end, so its last key (t = {last}) must come before duration_s \
                     ({duration} s{})",
                    if duration_s.is_none() {
                        ", from frames / 60"
                    } else {
                        ""
                    }
                ),
            ));
        }
        Ok(KeyedPath { keys, looped })
    }

    fn material(&self, raw: &Spanned<RawMaterial>) -> Result<Material, SceneError> {
        let r = raw.get_ref();
        let label = &format!("material {:?}", r.name.get_ref());
        let keys = present_keys!(r, albedo, checker, reflectance, ior, tint, radiance);
        match r.kind.get_ref().as_str() {
            "diffuse" => {
                self.only_keys(label, "a diffuse material", &keys, &["albedo", "checker"])?;
                let albedo = self.colour(
                    label,
                    "albedo",
                    self.required(label, "albedo", &r.albedo, raw)?,
                )?;
                let checker = match &r.checker {
                    Some(c) => {
                        let c = c.get_ref();
                        Some(Checker {
                            size: self.positive(label, "checker.size", &c.size)?,
                            albedo_b: self.colour(label, "checker.albedo_b", &c.albedo_b)?,
                        })
                    }
                    None => None,
                };
                Ok(Material::Diffuse { albedo, checker })
            }
            "mirror" => {
                self.only_keys(label, "a mirror material", &keys, &["reflectance"])?;
                let reflectance = self.colour(
                    label,
                    "reflectance",
                    self.required(label, "reflectance", &r.reflectance, raw)?,
                )?;
                Ok(Material::Mirror { reflectance })
            }
            "dielectric" => {
                self.only_keys(label, "a dielectric material", &keys, &["ior", "tint"])?;
                let ior = self.positive(label, "ior", self.required(label, "ior", &r.ior, raw)?)?;
                let tint = match &r.tint {
                    Some(t) => self.colour(label, "tint", t)?,
                    None => Vec3::ONE,
                };
                Ok(Material::Dielectric { ior, tint })
            }
            "emissive" => {
                self.only_keys(label, "an emissive material", &keys, &["radiance"])?;
                let radiance = self.colour(
                    label,
                    "radiance",
                    self.required(label, "radiance", &r.radiance, raw)?,
                )?;
                Ok(Material::Emissive { radiance })
            }
            other => Err(self.invalid(
                r.kind.span(),
                format!(
                    "{label}: unknown material type {other:?} \
                     (expected \"diffuse\", \"mirror\", \"dielectric\" or \"emissive\")"
                ),
            )),
        }
    }

    fn shape(&mut self, raw: &Spanned<RawShape>, name: &str) -> Result<Shape, SceneError> {
        let r = raw.get_ref();
        let label = &format!("shape {name:?}");
        let keys = r.present_keys();
        match r.kind.get_ref().as_str() {
            "sphere" => {
                self.only_keys(label, "a sphere", &keys, &["center", "radius"])?;
                let center = self.vec3(
                    label,
                    "center",
                    self.required(label, "center", &r.center, raw)?,
                )?;
                let radius = self.positive(
                    label,
                    "radius",
                    self.required(label, "radius", &r.radius, raw)?,
                )?;
                Ok(Shape::Sphere { center, radius })
            }
            "quad" => {
                self.only_keys(label, "a quad", &keys, &["corner", "edge_u", "edge_v"])?;
                let corner = self.vec3(
                    label,
                    "corner",
                    self.required(label, "corner", &r.corner, raw)?,
                )?;
                let eu = self.required(label, "edge_u", &r.edge_u, raw)?;
                let ev = self.required(label, "edge_v", &r.edge_v, raw)?;
                let edge_u = self.nonzero(label, "edge_u", eu)?;
                let edge_v = self.nonzero(label, "edge_v", ev)?;
                if edge_u.cross(edge_v).length() <= 1e-6 * edge_u.length() * edge_v.length() {
                    return Err(self.invalid(
                        ev.span(),
                        format!("{label}: edge_u {edge_u} and edge_v {edge_v} are parallel"),
                    ));
                }
                Ok(Shape::Quad {
                    corner,
                    edge_u,
                    edge_v,
                })
            }
            "plane" => {
                self.only_keys(label, "a plane", &keys, &["point", "normal"])?;
                let point = self.vec3(
                    label,
                    "point",
                    self.required(label, "point", &r.point, raw)?,
                )?;
                let normal = self.nonzero(
                    label,
                    "normal",
                    self.required(label, "normal", &r.normal, raw)?,
                )?;
                Ok(Shape::Plane {
                    point,
                    normal: unit(normal),
                })
            }
            "mesh" => {
                self.mesh_keys(label, &keys)?;
                self.mesh(raw, label)
            }
            other => Err(self.invalid(
                r.kind.span(),
                format!(
                    "{label}: unknown shape type {other:?} \
                     (expected \"sphere\", \"quad\", \"plane\" or \"mesh\")"
                ),
            )),
        }
    }

    fn mesh_keys(
        &self,
        label: &str,
        keys: &[(&'static str, Range<usize>)],
    ) -> Result<(), SceneError> {
        self.only_keys(
            label,
            "a mesh",
            keys,
            &[
                "path",
                "positions",
                "triangles",
                "translate",
                "scale",
                "rotate_y_deg",
                "instances",
            ],
        )
    }

    /// The parts of a glTF mesh shape that names no `material`: each part's mesh with the
    /// index of its material among the file's (label, material) pairs.
    #[allow(clippy::type_complexity)]
    fn gltf_parts(
        &mut self,
        raw: &Spanned<RawShape>,
        name: &str,
    ) -> Result<(Vec<(String, Material)>, Vec<(crate::TriangleMesh, usize)>), SceneError> {
        let r = raw.get_ref();
        let label = &format!("shape {name:?}");
        let keys = r.present_keys();
        self.mesh_keys(label, &keys)?;
        let transform = self.mesh_transform(r, label)?;
        let Some(path) = &r.path else {
            return Err(self.invalid(raw.span(), format!("{label}: missing `path`")));
        };
        let file = match self.base_dir {
            Some(dir) => dir.join(path.get_ref()),
            None => Path::new(path.get_ref()).to_owned(),
        };
        let imported =
            mesh_import::import_mesh_parts(&file, &Transform::IDENTITY).map_err(|e| {
                self.err(
                    path.span(),
                    SceneErrorKind::Mesh,
                    format!("{label}: mesh {:?}: {e}", path.get_ref()),
                )
            })?;
        let mut parts = Vec::with_capacity(imported.parts.len());
        let mut kept = 0;
        for part in imported.parts {
            self.check_placed(&part.mesh, &transform, path, label)?;
            kept += part.mesh.triangles.len();
            match part.material {
                Some(m) => parts.push((part.mesh, m)),
                None => {
                    return Err(self.err(
                        path.span(),
                        SceneErrorKind::Mesh,
                        format!(
                            "{label}: mesh {:?}: {} triangles belong to glTF primitives with \
                             no material; give the shape a `material` (it then applies to the \
                             whole file)",
                            path.get_ref(),
                            part.mesh.triangles.len()
                        ),
                    ));
                }
            }
        }
        if imported.degenerate_dropped > 0 {
            let line = line_of(self.text, raw.span().start);
            self.notes.push(format!(
                "{}:{line}: {label}: dropped {} degenerate (zero-area) triangles, kept {kept}",
                self.origin, imported.degenerate_dropped,
            ));
        }
        Ok((imported.materials, parts))
    }

    fn mesh_transform(&self, r: &RawShape, label: &str) -> Result<Transform, SceneError> {
        self.transform(label, &r.translate, &r.rotate_y_deg, &r.scale)
    }

    /// Checks that `placement` keeps every vertex of `mesh` finite; `at` is the key the
    /// mesh came from.
    fn check_placed<T>(
        &self,
        mesh: &crate::TriangleMesh,
        placement: &Transform,
        at: &Spanned<T>,
        label: &str,
    ) -> Result<(), SceneError> {
        match mesh
            .positions
            .iter()
            .enumerate()
            .find(|(_, p)| !placement.apply(**p).is_finite())
        {
            Some((vertex, &p)) => Err(self.err(
                at.span(),
                SceneErrorKind::Mesh,
                format!(
                    "{label}: vertex {vertex} {p} is not finite once placed: {}",
                    placement.apply(p)
                ),
            )),
            None => Ok(()),
        }
    }

    fn mesh(&mut self, raw: &Spanned<RawShape>, label: &str) -> Result<Shape, SceneError> {
        let r = raw.get_ref();
        let placement = self.mesh_transform(r, label)?;
        let imported = match (&r.path, &r.positions, &r.triangles) {
            (Some(path), None, None) => {
                let file = match self.base_dir {
                    Some(dir) => dir.join(path.get_ref()),
                    None => Path::new(path.get_ref()).to_owned(),
                };
                let imported =
                    mesh_import::import_mesh(&file, &Transform::IDENTITY).map_err(|e| {
                        self.err(
                            path.span(),
                            SceneErrorKind::Mesh,
                            format!("{label}: mesh {:?}: {e}", path.get_ref()),
                        )
                    })?;
                self.check_placed(&imported.mesh, &placement, path, label)?;
                imported
            }
            (None, Some(p), Some(t)) => {
                let positions = p.get_ref().iter().map(|&v| Vec3::from(v)).collect();
                let imported =
                    mesh_import::build_mesh(positions, t.get_ref().clone(), &Transform::IDENTITY)
                        .map_err(|e| {
                        self.err(p.span(), SceneErrorKind::Mesh, format!("{label}: {e}"))
                    })?;
                self.check_placed(&imported.mesh, &placement, p, label)?;
                imported
            }
            _ => {
                return Err(self.invalid(
                    raw.span(),
                    format!(
                        "{label}: a mesh needs either `path` (a mesh file) or both \
                         `positions` and `triangles`, not both"
                    ),
                ));
            }
        };
        if imported.degenerate_dropped > 0 {
            let line = line_of(self.text, raw.span().start);
            self.notes.push(format!(
                "{}:{line}: {label}: dropped {} degenerate (zero-area) triangles, kept {}",
                self.origin,
                imported.degenerate_dropped,
                imported.mesh.triangles.len()
            ));
        }
        Ok(Shape::Mesh {
            mesh: imported.mesh,
            placement,
            instances: self.instances(r, label)?,
        })
    }

    /// The `instances` of a mesh shape: none, or a non-empty list of transforms.
    fn instances(&self, r: &RawShape, label: &str) -> Result<Vec<Transform>, SceneError> {
        let Some(list) = &r.instances else {
            return Ok(Vec::new());
        };
        if list.get_ref().is_empty() {
            return Err(self.invalid(
                list.span(),
                format!(
                    "{label}: instances must list at least one copy (leave the key out for a \
                     single copy)"
                ),
            ));
        }
        list.get_ref()
            .iter()
            .enumerate()
            .map(|(i, inst)| {
                let ir = inst.get_ref();
                self.transform(
                    &format!("{label}: instance {}", i + 1),
                    &ir.translate,
                    &ir.rotate_y_deg,
                    &ir.scale,
                )
            })
            .collect()
    }

    /// A transform from its optional parts, each finite, the scale also non-zero.
    fn transform(
        &self,
        label: &str,
        translate: &Option<Spanned<V3>>,
        rotate_y_deg: &Option<Spanned<f32>>,
        scale: &Option<Spanned<Triple>>,
    ) -> Result<Transform, SceneError> {
        let mut transform = Transform::IDENTITY;
        if let Some(t) = translate {
            transform.translate = self.vec3(label, "translate", t)?;
        }
        if let Some(s) = scale {
            transform.scale = self.scale(label, s)?;
        }
        if let Some(a) = rotate_y_deg {
            transform.rotate_y_deg = self.number(label, "rotate_y_deg", a)?;
        }
        Ok(transform)
    }

    fn scale(&self, label: &str, s: &Spanned<Triple>) -> Result<Vec3, SceneError> {
        let scale = Vec3::from(s.get_ref().0);
        if !scale.is_finite() || scale.cmpeq(Vec3::ZERO).any() {
            return Err(self.invalid(
                s.span(),
                format!("{label}: scale must be finite and non-zero, got {scale}"),
            ));
        }
        Ok(scale)
    }

    /// The `[shapes.motion]` table of shape `name`, if any.
    fn shape_motion(&self, r: &RawShape, name: &str) -> Result<Option<Motion>, SceneError> {
        let Some(raw) = &r.motion else {
            return Ok(None);
        };
        let label = &format!("shape {name:?}: motion");
        let kind = r.kind.get_ref().as_str();
        if kind == "plane" {
            return Err(self.invalid(
                raw.span(),
                format!(
                    "shape {name:?}: a plane cannot move (it is infinite); use a quad for a \
                     moving floor or wall"
                ),
            ));
        }
        let m = raw.get_ref();
        let mut keys: Vec<MotionKey> = Vec::new();
        if let Some(list) = &m.keys {
            for (i, k) in list.get_ref().iter().enumerate() {
                let key_label = &format!("{label}: key {}", i + 1);
                let kr = k.get_ref();
                let t = self.seconds(key_label, "t", &kr.t)?;
                if let Some(prev) = keys.last()
                    && t <= prev.t
                {
                    return Err(self.invalid(
                        kr.t.span(),
                        format!(
                            "{key_label}: key times must increase, but t = {t} is not after \
                             key {i}'s t = {}",
                            prev.t
                        ),
                    ));
                }
                let scale = match &kr.scale {
                    Some(s) => {
                        let v = self.scale(key_label, s)?;
                        if kind == "sphere" && !(v.x == v.y && v.y == v.z) {
                            return Err(self.invalid(
                                s.span(),
                                format!(
                                    "{key_label}: a sphere stays a sphere, so its scale must be \
                                     one number, got {v}"
                                ),
                            ));
                        }
                        Some(v)
                    }
                    None => None,
                };
                keys.push(MotionKey {
                    t,
                    translate: match &kr.translate {
                        Some(v) => Some(self.vec3(key_label, "translate", v)?),
                        None => None,
                    },
                    rotate_y_deg: match &kr.rotate_y_deg {
                        Some(a) => Some(self.number(key_label, "rotate_y_deg", a)?),
                        None => None,
                    },
                    scale,
                });
            }
            if keys.is_empty() {
                return Err(self.invalid(
                    list.span(),
                    format!("{label}: keys must list at least one key"),
                ));
            }
        }
        let looped = m.looped.as_ref().is_some_and(|l| *l.get_ref());
        if looped {
            let span = m.looped.as_ref().map_or(raw.span(), |l| l.span());
            let (Some(first), Some(last)) = (keys.first(), keys.last()) else {
                return Err(self.invalid(span, format!("{label}: loop needs keys to repeat")));
            };
            if keys.len() < 2
                || (first.translate, first.rotate_y_deg, first.scale)
                    != (last.translate, last.rotate_y_deg, last.scale)
            {
                return Err(self.invalid(
                    span,
                    format!(
                        "{label}: a looped motion's last key closes the lap, so it must repeat \
                         the first key's translate, rotate_y_deg and scale (at a later t)"
                    ),
                ));
            }
        }
        let spin_deg_per_s = match &m.spin_deg_per_s {
            Some(s) => self.number(label, "spin_deg_per_s", s)?,
            None => 0.0,
        };
        let visible = match &m.visible {
            Some(list) => Some(self.visible(list, label)?),
            None => None,
        };
        Ok(Some(Motion {
            keys,
            looped,
            spin_deg_per_s,
            visible,
        }))
    }

    /// Visibility intervals: at least one, each [start, end) not empty, in increasing order
    /// without overlaps.
    fn visible(
        &self,
        list: &Spanned<Vec<Spanned<[f64; 2]>>>,
        label: &str,
    ) -> Result<Vec<[f64; 2]>, SceneError> {
        if list.get_ref().is_empty() {
            return Err(self.invalid(
                list.span(),
                format!(
                    "{label}: visible must list at least one [start, end] interval (leave it \
                     out for always)"
                ),
            ));
        }
        let mut spans: Vec<[f64; 2]> = Vec::new();
        for (i, v) in list.get_ref().iter().enumerate() {
            let [start, end] = *v.get_ref();
            let which = format!("{label}: visible interval {}", i + 1);
            if !(start.is_finite() && end.is_finite()) {
                return Err(self.invalid(
                    v.span(),
                    format!("{which} [{start}, {end}] must be finite numbers of seconds"),
                ));
            }
            if end <= start {
                return Err(self.invalid(
                    v.span(),
                    format!("{which} [{start}, {end}] is empty: its end must be after its start"),
                ));
            }
            if let Some(&[p_start, p_end]) = spans.last()
                && start < p_end
            {
                return Err(self.invalid(
                    v.span(),
                    format!(
                        "{which} [{start}, {end}] overlaps or precedes interval {i} \
                         [{p_start}, {p_end}]: list the intervals in time order, apart"
                    ),
                ));
            }
            spans.push([start, end]);
        }
        Ok(spans)
    }

    /// Rejects keys of `keys` that are not in `allowed` for a table of this kind.
    fn only_keys(
        &self,
        label: &str,
        kind: &str,
        keys: &[(&'static str, Range<usize>)],
        allowed: &[&str],
    ) -> Result<(), SceneError> {
        match keys.iter().find(|(k, _)| !allowed.contains(k)) {
            Some((key, span)) => Err(self.invalid(
                span.clone(),
                format!(
                    "{label}: key `{key}` does not apply to {kind} (it takes {})",
                    if allowed.is_empty() {
                        "only `frames` and `duration_s`".to_owned()
                    } else {
                        allowed
                            .iter()
                            .map(|k| format!("`{k}`"))
                            .collect::<Vec<_>>()
                            .join(", ")
                    }
                ),
            )),
            None => Ok(()),
        }
    }

    fn required<'v, T, U>(
        &self,
        label: &str,
        key: &str,
        value: &'v Option<Spanned<T>>,
        table: &Spanned<U>,
    ) -> Result<&'v Spanned<T>, SceneError> {
        value
            .as_ref()
            .ok_or_else(|| self.invalid(table.span(), format!("{label}: missing `{key}`")))
    }

    fn number(&self, label: &str, key: &str, v: &Spanned<f32>) -> Result<f32, SceneError> {
        let x = *v.get_ref();
        if x.is_finite() {
            Ok(x)
        } else {
            Err(self.invalid(
                v.span(),
                format!("{label}: {key} must be a finite number, got {x}"),
            ))
        }
    }

    fn field_of_view(&self, label: &str, v: &Spanned<f32>) -> Result<f32, SceneError> {
        let f = self.number(label, "vfov_deg", v)?;
        if f > 0.0 && f < 180.0 {
            Ok(f)
        } else {
            Err(self.invalid(
                v.span(),
                format!("{label}: vfov_deg must be in (0, 180) degrees, got {f}"),
            ))
        }
    }

    /// A time in seconds: any finite number.
    fn seconds(&self, label: &str, key: &str, v: &Spanned<f64>) -> Result<f64, SceneError> {
        let x = *v.get_ref();
        if x.is_finite() {
            Ok(x)
        } else {
            Err(self.invalid(
                v.span(),
                format!("{label}: {key} must be a finite number of seconds, got {x}"),
            ))
        }
    }

    fn positive_seconds(
        &self,
        label: &str,
        key: &str,
        v: &Spanned<f64>,
    ) -> Result<f64, SceneError> {
        let x = self.seconds(label, key, v)?;
        if x > 0.0 {
            Ok(x)
        } else {
            Err(self.invalid(
                v.span(),
                format!("{label}: {key} must be positive, got {x}"),
            ))
        }
    }

    fn positive(&self, label: &str, key: &str, v: &Spanned<f32>) -> Result<f32, SceneError> {
        let x = self.number(label, key, v)?;
        if x > 0.0 {
            Ok(x)
        } else {
            Err(self.invalid(
                v.span(),
                format!("{label}: {key} must be positive, got {x}"),
            ))
        }
    }

    fn non_negative(&self, label: &str, key: &str, v: &Spanned<f32>) -> Result<f32, SceneError> {
        let x = self.number(label, key, v)?;
        if x >= 0.0 {
            Ok(x)
        } else {
            Err(self.invalid(
                v.span(),
                format!("{label}: {key} must not be negative, got {x}"),
            ))
        }
    }

    fn vec3(&self, label: &str, key: &str, v: &Spanned<V3>) -> Result<Vec3, SceneError> {
        let p = Vec3::from(*v.get_ref());
        if p.is_finite() {
            Ok(p)
        } else {
            Err(self.invalid(v.span(), format!("{label}: {key} must be finite, got {p}")))
        }
    }

    fn nonzero(&self, label: &str, key: &str, v: &Spanned<V3>) -> Result<Vec3, SceneError> {
        let p = self.vec3(label, key, v)?;
        if p != Vec3::ZERO {
            Ok(p)
        } else {
            Err(self.invalid(v.span(), format!("{label}: {key} must not be zero-length")))
        }
    }

    /// A colour (or intensity): finite and not negative.
    fn colour(&self, label: &str, key: &str, v: &Spanned<Triple>) -> Result<Vec3, SceneError> {
        let c = Vec3::from(v.get_ref().0);
        if !c.is_finite() {
            return Err(self.invalid(v.span(), format!("{label}: {key} must be finite, got {c}")));
        }
        if c.min_element() < 0.0 {
            return Err(self.invalid(
                v.span(),
                format!("{label}: {key} must not be negative, got {c}"),
            ));
        }
        Ok(c)
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
