//! The scene file's schema: what serde reads from the TOML, with the spans of its values
//! for messages.

use super::*;

/// Three numbers, or one number meaning all three (grey colours, uniform scale).
#[derive(Clone, Copy, Debug)]
pub(super) struct Triple(pub(super) [f32; 3]);

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

pub(super) type V3 = [f32; 3];

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawScene {
    pub(super) name: Option<Spanned<String>>,
    pub(super) background: Option<Spanned<Triple>>,
    pub(super) ambient: Option<Spanned<f32>>,
    pub(super) camera: Spanned<RawCamera>,
    pub(super) path: Option<Spanned<RawPath>>,
    #[serde(default)]
    pub(super) materials: Vec<Spanned<RawMaterial>>,
    #[serde(default)]
    pub(super) shapes: Vec<Spanned<RawShape>>,
    #[serde(default)]
    pub(super) lights: Vec<Spanned<RawLight>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawCamera {
    pub(super) eye: Spanned<V3>,
    pub(super) target: Option<Spanned<V3>>,
    pub(super) forward: Option<Spanned<V3>>,
    pub(super) yaw_deg: Option<Spanned<f32>>,
    pub(super) pitch_deg: Option<Spanned<f32>>,
    pub(super) up: Option<Spanned<V3>>,
    pub(super) vfov_deg: Option<Spanned<f32>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawPath {
    #[serde(rename = "type")]
    pub(super) kind: Spanned<String>,
    pub(super) frames: Option<Spanned<u32>>,
    pub(super) duration_s: Option<Spanned<f64>>,
    pub(super) center: Option<Spanned<V3>>,
    pub(super) radius: Option<Spanned<f32>>,
    pub(super) height: Option<Spanned<f32>>,
    #[serde(rename = "loop")]
    pub(super) looped: Option<Spanned<bool>>,
    pub(super) keys: Option<Spanned<Vec<Spanned<RawCameraKey>>>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawCameraKey {
    pub(super) t: Spanned<f64>,
    pub(super) eye: Spanned<V3>,
    pub(super) target: Option<Spanned<V3>>,
    pub(super) yaw_deg: Option<Spanned<f32>>,
    pub(super) pitch_deg: Option<Spanned<f32>>,
    pub(super) vfov_deg: Option<Spanned<f32>>,
}

/// A mesh instance's transform.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawTransform {
    pub(super) translate: Option<Spanned<V3>>,
    pub(super) rotate_y_deg: Option<Spanned<f32>>,
    pub(super) scale: Option<Spanned<Triple>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawMotion {
    pub(super) keys: Option<Spanned<Vec<Spanned<RawMotionKey>>>>,
    #[serde(rename = "loop")]
    pub(super) looped: Option<Spanned<bool>>,
    pub(super) spin_deg_per_s: Option<Spanned<f32>>,
    pub(super) visible: Option<Spanned<Vec<Spanned<[f64; 2]>>>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawMotionKey {
    pub(super) t: Spanned<f64>,
    pub(super) translate: Option<Spanned<V3>>,
    pub(super) rotate_y_deg: Option<Spanned<f32>>,
    pub(super) scale: Option<Spanned<Triple>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawMaterial {
    pub(super) name: Spanned<String>,
    #[serde(rename = "type")]
    pub(super) kind: Spanned<String>,
    pub(super) albedo: Option<Spanned<Triple>>,
    pub(super) checker: Option<Spanned<RawChecker>>,
    pub(super) reflectance: Option<Spanned<Triple>>,
    pub(super) ior: Option<Spanned<f32>>,
    pub(super) tint: Option<Spanned<Triple>>,
    pub(super) radiance: Option<Spanned<Triple>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawChecker {
    pub(super) size: Spanned<f32>,
    pub(super) albedo_b: Spanned<Triple>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawShape {
    pub(super) name: Spanned<String>,
    #[serde(rename = "type")]
    pub(super) kind: Spanned<String>,
    pub(super) material: Option<Spanned<String>>,
    pub(super) center: Option<Spanned<V3>>,
    pub(super) radius: Option<Spanned<f32>>,
    pub(super) corner: Option<Spanned<V3>>,
    pub(super) edge_u: Option<Spanned<V3>>,
    pub(super) edge_v: Option<Spanned<V3>>,
    pub(super) point: Option<Spanned<V3>>,
    pub(super) normal: Option<Spanned<V3>>,
    pub(super) path: Option<Spanned<String>>,
    pub(super) positions: Option<Spanned<Vec<V3>>>,
    pub(super) triangles: Option<Spanned<Vec<[u32; 3]>>>,
    pub(super) translate: Option<Spanned<V3>>,
    pub(super) scale: Option<Spanned<Triple>>,
    pub(super) rotate_y_deg: Option<Spanned<f32>>,
    pub(super) instances: Option<Spanned<Vec<Spanned<RawTransform>>>>,
    pub(super) motion: Option<Spanned<RawMotion>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawLight {
    pub(super) position: Spanned<V3>,
    pub(super) intensity: Spanned<Triple>,
}

impl RawShape {
    /// The optional keys this shape entry sets, with their spans, for the per-type checks.
    pub(super) fn present_keys(&self) -> Vec<(&'static str, Range<usize>)> {
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
