//! Writing a [`Scene`] back as a TOML scene file that reads back to the identical scene:
//! every float is written in Rust's shortest round-trip form, meshes as inline triangle data.

use crate::format::yaw_pitch_deg_camera;
use crate::{Camera, KeyLook, Material, Motion, PathMotion, Scene, Shape, Transform};
use glam::Vec3;
use std::fmt::Write;

/// The scene as TOML in the format of `docs/scene-format.md`, such that
/// `parse_scene(&scene_to_toml(s), ..) == Ok(s)` bit for bit, for any valid scene.
///
/// The camera is written with `yaw_deg`/`pitch_deg` when those reproduce its view
/// direction exactly, else with `forward`. Meshes are written inline (`positions` and
/// `triangles`), since a scene keeps no link to the files its meshes came from.
pub fn scene_to_toml(scene: &Scene) -> String {
    let mut w = String::new();
    // Writing into a String cannot fail.
    let _ = write_scene(&mut w, scene);
    w
}

fn write_scene(w: &mut String, s: &Scene) -> std::fmt::Result {
    writeln!(w, "name = {}", string(&s.name))?;
    writeln!(w, "background = {}", triple(s.background))?;
    writeln!(w, "ambient = {}", float(s.ambient))?;

    writeln!(w, "\n[camera]")?;
    write_camera(w, &s.camera)?;

    writeln!(w, "\n[path]")?;
    match &s.path.motion {
        PathMotion::Sweep => writeln!(w, "type = \"sweep\"")?,
        PathMotion::Pans => writeln!(w, "type = \"pans\"")?,
        PathMotion::Orbit {
            center,
            radius,
            height,
        } => {
            writeln!(w, "type = \"orbit\"")?;
            writeln!(w, "center = {}", vec3(*center))?;
            writeln!(w, "radius = {}", float(*radius))?;
            writeln!(w, "height = {}", float(*height))?;
        }
        PathMotion::Keys(keyed) => {
            writeln!(w, "type = \"keys\"\nloop = {}", keyed.looped)?;
        }
    }
    writeln!(w, "frames = {}", s.path.frames)?;
    if let Some(d) = s.path.duration_s {
        writeln!(w, "duration_s = {}", seconds(d))?;
    }
    if let PathMotion::Keys(keyed) = &s.path.motion {
        for k in &keyed.keys {
            writeln!(w, "\n[[path.keys]]\nt = {}", seconds(k.t))?;
            writeln!(w, "eye = {}", vec3(k.eye))?;
            match k.look {
                KeyLook::Target(t) => writeln!(w, "target = {}", vec3(t))?,
                KeyLook::YawPitch { yaw_deg, pitch_deg } => writeln!(
                    w,
                    "yaw_deg = {}\npitch_deg = {}",
                    float(yaw_deg),
                    float(pitch_deg)
                )?,
            }
            if let Some(f) = k.vfov_deg {
                writeln!(w, "vfov_deg = {}", float(f))?;
            }
        }
    }

    for (name, m) in &s.materials {
        writeln!(w, "\n[[materials]]\nname = {}", string(name))?;
        match m {
            Material::Diffuse { albedo, checker } => {
                writeln!(w, "type = \"diffuse\"\nalbedo = {}", triple(*albedo))?;
                if let Some(c) = checker {
                    writeln!(
                        w,
                        "checker = {{ size = {}, albedo_b = {} }}",
                        float(c.size),
                        triple(c.albedo_b)
                    )?;
                }
            }
            Material::Mirror { reflectance } => {
                writeln!(
                    w,
                    "type = \"mirror\"\nreflectance = {}",
                    triple(*reflectance)
                )?;
            }
            Material::Dielectric { ior, tint } => {
                writeln!(w, "type = \"dielectric\"\nior = {}", float(*ior))?;
                writeln!(w, "tint = {}", triple(*tint))?;
            }
            Material::Emissive { radiance } => {
                writeln!(w, "type = \"emissive\"\nradiance = {}", triple(*radiance))?;
            }
        }
    }

    for o in &s.objects {
        writeln!(w, "\n[[shapes]]\nname = {}", string(&o.name))?;
        let material = s.materials.get(o.material).map_or("", |(n, _)| n.as_str());
        match &o.shape {
            Shape::Sphere { center, radius } => {
                writeln!(w, "type = \"sphere\"\nmaterial = {}", string(material))?;
                writeln!(w, "center = {}\nradius = {}", vec3(*center), float(*radius))?;
            }
            Shape::Quad {
                corner,
                edge_u,
                edge_v,
            } => {
                writeln!(w, "type = \"quad\"\nmaterial = {}", string(material))?;
                writeln!(w, "corner = {}", vec3(*corner))?;
                writeln!(w, "edge_u = {}\nedge_v = {}", vec3(*edge_u), vec3(*edge_v))?;
            }
            Shape::Plane { point, normal } => {
                writeln!(w, "type = \"plane\"\nmaterial = {}", string(material))?;
                writeln!(w, "point = {}\nnormal = {}", vec3(*point), vec3(*normal))?;
            }
            Shape::Mesh {
                mesh,
                placement,
                instances,
            } => {
                writeln!(w, "type = \"mesh\"\nmaterial = {}", string(material))?;
                writeln!(w, "positions = [")?;
                for p in &mesh.positions {
                    writeln!(w, "  {},", vec3(*p))?;
                }
                writeln!(w, "]\ntriangles = [")?;
                for [a, b, c] in &mesh.triangles {
                    writeln!(w, "  [{a}, {b}, {c}],")?;
                }
                writeln!(w, "]")?;
                for (key, value) in transform_keys(placement) {
                    writeln!(w, "{key} = {value}")?;
                }
                if !instances.is_empty() {
                    writeln!(w, "instances = [")?;
                    for i in instances {
                        let keys: Vec<String> = transform_keys(i)
                            .into_iter()
                            .map(|(k, v)| format!("{k} = {v}"))
                            .collect();
                        writeln!(w, "  {{ {} }},", keys.join(", "))?;
                    }
                    writeln!(w, "]")?;
                }
            }
        }
        if let Some(m) = &o.motion {
            write_motion(w, m)?;
        }
    }

    for l in &s.lights {
        writeln!(w, "\n[[lights]]")?;
        writeln!(w, "position = {}", vec3(l.position))?;
        writeln!(w, "intensity = {}", triple(l.intensity))?;
    }
    Ok(())
}

/// The keys of a transform whose values differ from the identity's (bit for bit, so that
/// -0.0 is written), as (key, TOML value).
fn transform_keys(t: &Transform) -> Vec<(&'static str, String)> {
    let bits = |v: Vec3| v.to_array().map(f32::to_bits);
    let id = Transform::IDENTITY;
    let mut keys = Vec::new();
    if bits(t.translate) != bits(id.translate) {
        keys.push(("translate", vec3(t.translate)));
    }
    if t.rotate_y_deg.to_bits() != id.rotate_y_deg.to_bits() {
        keys.push(("rotate_y_deg", float(t.rotate_y_deg)));
    }
    if bits(t.scale) != bits(id.scale) {
        keys.push(("scale", triple(t.scale)));
    }
    keys
}

/// A `[shapes.motion]` table and its keys, after the shape's own keys.
fn write_motion(w: &mut String, m: &Motion) -> std::fmt::Result {
    writeln!(w, "\n[shapes.motion]\nloop = {}", m.looped)?;
    writeln!(w, "spin_deg_per_s = {}", float(m.spin_deg_per_s))?;
    if let Some(spans) = &m.visible {
        let spans: Vec<String> = spans
            .iter()
            .map(|[a, b]| format!("[{}, {}]", seconds(*a), seconds(*b)))
            .collect();
        writeln!(w, "visible = [{}]", spans.join(", "))?;
    }
    for k in &m.keys {
        writeln!(w, "\n[[shapes.motion.keys]]\nt = {}", seconds(k.t))?;
        if let Some(t) = k.translate {
            writeln!(w, "translate = {}", vec3(t))?;
        }
        if let Some(a) = k.rotate_y_deg {
            writeln!(w, "rotate_y_deg = {}", float(a))?;
        }
        if let Some(s) = k.scale {
            writeln!(w, "scale = {}", triple(s))?;
        }
    }
    Ok(())
}

fn write_camera(w: &mut String, c: &Camera) -> std::fmt::Result {
    writeln!(w, "eye = {}", vec3(c.eye))?;
    let f = c.forward;
    let yaw_deg = (-f.x).atan2(-f.z).to_degrees();
    let pitch_deg = (f.y / f.length()).clamp(-1.0, 1.0).asin().to_degrees();
    let again = yaw_pitch_deg_camera(c.eye, yaw_deg, pitch_deg, c.up, c.vfov_deg);
    if again.forward.to_array().map(f32::to_bits) == f.to_array().map(f32::to_bits) {
        writeln!(
            w,
            "yaw_deg = {}\npitch_deg = {}",
            float(yaw_deg),
            float(pitch_deg)
        )?;
    } else {
        writeln!(w, "forward = {}", vec3(f))?;
    }
    writeln!(w, "up = {}", vec3(c.up))?;
    writeln!(w, "vfov_deg = {}", float(c.vfov_deg))
}

/// An `f32` as a TOML float that reads back (TOML floats are read as `f64`, then rounded
/// to `f32`) to the same bits: Rust's shortest round-trip form, or, in the rare case where
/// rounding through `f64` would land elsewhere, the exact `f64` value's shortest form.
pub(crate) fn float(x: f32) -> String {
    let short = format!("{x:?}");
    if short
        .parse::<f64>()
        .is_ok_and(|d| (d as f32).to_bits() == x.to_bits())
    {
        short
    } else {
        format!("{:?}", f64::from(x))
    }
}

/// A time in seconds (an `f64`) as a TOML float that reads back to the same bits.
fn seconds(x: f64) -> String {
    format!("{x:?}")
}

fn vec3(v: Vec3) -> String {
    format!("[{}, {}, {}]", float(v.x), float(v.y), float(v.z))
}

/// A colour or intensity: one number when all three channels are the same.
fn triple(v: Vec3) -> String {
    if v.x.to_bits() == v.y.to_bits() && v.y.to_bits() == v.z.to_bits() {
        float(v.x)
    } else {
        vec3(v)
    }
}

/// A TOML basic string.
fn string(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            '\r' => out.push_str("\\r"),
            c if c.is_control() => {
                let _ = write!(out, "\\u{:04X}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floats_are_shortest_and_valid_toml() {
        assert_eq!(float(0.5), "0.5");
        assert_eq!(float(60.0), "60.0");
        assert_eq!(float(-0.0), "-0.0");
        assert_eq!(float(0.1), "0.1");
        for x in [
            1e-7f32,
            3.4e38,
            f32::MIN_POSITIVE,
            f32::MAX,
            f32::from_bits(1),
            0.3,
            1.0 / 3.0,
        ] {
            let doc = format!("x = {}", float(x));
            let back: toml::Table = toml::from_str(&doc).unwrap();
            let y = back["x"].as_float().unwrap() as f32;
            assert_eq!(y.to_bits(), x.to_bits(), "{doc}");
        }
    }

    #[test]
    fn strings_are_escaped() {
        let s = "a \"b\" \\ c\n\u{1}";
        let doc = format!("x = {}", string(s));
        let back: toml::Table = toml::from_str(&doc).unwrap();
        assert_eq!(back["x"].as_str().unwrap(), s);
    }
}
