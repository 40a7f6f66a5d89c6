//! Light sources.

use glam::Vec3;

/// A point light. The irradiance it gives a surface at distance d facing it is
/// `intensity / d²` (linear RGB); see `docs/shading.md`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLight {
    /// World-space position.
    pub position: Vec3,
    /// Linear RGB intensity: the irradiance the light gives at 1 m, head on.
    pub intensity: Vec3,
}
