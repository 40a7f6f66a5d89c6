//! Light sources.

use glam::Vec3;

/// A point light. The irradiance it gives a surface at distance d facing it is
/// `intensity / d²` (linear RGB); see `docs/shading.md`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLight {
    pub position: Vec3,
    pub intensity: Vec3,
}
