//! How a shape moves and when it exists: keyed transforms, a constant spin and visibility
//! intervals, all functions of scene time t in seconds (`[shapes.motion]` in
//! `docs/scene-format.md`).
//!
//! Motion acts about the shape's placement origin O (a mesh's `translate`, a sphere's
//! centre, a quad's corner): a point at offset x from O (after the shape's own placement
//! and its instance's transform) is at
//!
//! O + translate(t) + R_y(rotate_y_deg(t)) · scale(t) · R_y(spin_deg_per_s · t) · x.

use crate::spline::{Curve, Ends, interpolate};
use crate::transform::rotation_y;
use glam::{DAffine3, DMat3, DVec3, Vec3};

/// The motion of one shape.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Motion {
    /// Keyed transforms, times strictly increasing; empty: no keyed motion.
    pub keys: Vec<MotionKey>,
    /// Whether the keyed motion repeats, with the period from the first key to the last (the
    /// last key closes the lap, so it repeats the first key's values).
    pub looped: bool,
    /// Rotation about +y through the placement origin, degrees per second.
    pub spin_deg_per_s: f32,
    /// The intervals [start, end) of scene time in which the shape exists, in increasing
    /// order and not overlapping; `None`: always.
    pub visible: Option<Vec<[f64; 2]>>,
}

/// One key of a [`Motion`]: the shape's extra transform at time `t`. Each component is
/// interpolated between the keys that give it (translate and rotation along the C1 spline of
/// `crate::spline`, scale along straight segments, so it never overshoots); before the first
/// and after the last key that gives it, it holds; a component no key gives is the identity.
#[derive(Clone, Debug, PartialEq)]
pub struct MotionKey {
    /// Seconds.
    pub t: f64,
    /// World-space translation; `None`: this key does not give it.
    pub translate: Option<Vec3>,
    /// Rotation about +y, degrees; `None`: this key does not give it.
    pub rotate_y_deg: Option<f32>,
    /// Per axis; a sphere's is uniform.
    pub scale: Option<Vec3>,
}

impl Motion {
    /// Whether the shape exists at time `t`.
    pub fn is_visible(&self, t: f64) -> bool {
        self.visible
            .as_ref()
            .is_none_or(|spans| spans.iter().any(|&[start, end]| start <= t && t < end))
    }

    /// The keyed transform at time `t`: translation, rotation about +y in degrees, and scale.
    pub fn keyed_at(&self, t: f64) -> (DVec3, f64, DVec3) {
        let ends = match (self.looped, self.keys.first(), self.keys.last()) {
            (true, Some(first), Some(last)) => Ends::Cyclic(last.t - first.t),
            _ => Ends::Open,
        };
        let track = |value: &dyn Fn(&MotionKey) -> Option<DVec3>, curve| {
            let mut keys: Vec<(f64, DVec3)> = self
                .keys
                .iter()
                .filter_map(|k| value(k).map(|v| (k.t, v)))
                .collect();
            if let Ends::Cyclic(period) = ends
                && keys.len() > 1
                && keys[keys.len() - 1].0 - keys[0].0 >= period
            {
                // The lap's closing key is the first key a period later.
                keys.pop();
            }
            (!keys.is_empty()).then(|| interpolate(&keys, ends, curve, t))
        };
        let translate = track(&|k| k.translate.map(DVec3::from), Curve::Smooth);
        let rotate = track(
            &|k| k.rotate_y_deg.map(|a| DVec3::splat(a.into())),
            Curve::Smooth,
        );
        let scale = track(&|k| k.scale.map(DVec3::from), Curve::Linear);
        (
            translate.unwrap_or(DVec3::ZERO),
            rotate.map_or(0.0, |r| r.x),
            scale.unwrap_or(DVec3::ONE),
        )
    }

    /// The motion at time `t` as an affine map of offsets from the placement origin (the
    /// module documentation's formula without O).
    pub fn offset_at(&self, t: f64) -> DAffine3 {
        let (translate, rotate_deg, scale) = self.keyed_at(t);
        let spin = rotation_y(f64::from(self.spin_deg_per_s) * t);
        DAffine3 {
            matrix3: rotation_y(rotate_deg) * DMat3::from_diagonal(scale) * spin,
            translation: translate,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(t: f64, translate: Option<[f32; 3]>, scale: Option<f32>) -> MotionKey {
        MotionKey {
            t,
            translate: translate.map(Vec3::from),
            rotate_y_deg: None,
            scale: scale.map(Vec3::splat),
        }
    }

    #[test]
    fn visibility_intervals_are_half_open() {
        let m = Motion {
            visible: Some(vec![[1.0, 2.0], [3.0, 3.5]]),
            ..Default::default()
        };
        assert!(!m.is_visible(0.5));
        assert!(m.is_visible(1.0));
        assert!(m.is_visible(1.999));
        assert!(!m.is_visible(2.0));
        assert!(m.is_visible(3.2));
        assert!(!m.is_visible(4.0));
        assert!(Motion::default().is_visible(-5.0));
    }

    #[test]
    fn components_interpolate_over_the_keys_that_give_them() {
        let m = Motion {
            keys: vec![
                key(0.0, Some([0.0, 0.0, 0.0]), Some(1.0)),
                key(1.0, None, Some(3.0)),
                key(2.0, Some([4.0, 0.0, 0.0]), None),
            ],
            ..Default::default()
        };
        let (t, r, s) = m.keyed_at(1.0);
        assert!((t - DVec3::new(2.0, 0.0, 0.0)).length() < 1e-12, "{t}");
        assert_eq!(r, 0.0);
        assert_eq!(s, DVec3::splat(3.0));
        // Scale holds after its last key; translation holds after its last key.
        assert_eq!(m.keyed_at(5.0).2, DVec3::splat(3.0));
        assert_eq!(m.keyed_at(5.0).0, DVec3::new(4.0, 0.0, 0.0));
        // Linear scale halfway between 1 and 3.
        assert_eq!(m.keyed_at(0.5).2, DVec3::splat(2.0));
    }

    #[test]
    fn looped_motion_repeats_its_lap() {
        let m = Motion {
            keys: vec![
                key(1.0, Some([0.0, 0.0, 0.0]), None),
                key(2.0, Some([1.0, 0.0, 0.0]), None),
                key(3.0, Some([0.0, 0.0, 0.0]), None),
            ],
            looped: true,
            ..Default::default()
        };
        for t in [1.25, 1.7, 2.4] {
            let a = m.keyed_at(t).0;
            let b = m.keyed_at(t + 2.0).0;
            assert!((a - b).length() < 1e-12, "{t}: {a} vs {b}");
        }
        assert!((m.keyed_at(4.0).0 - DVec3::X).length() < 1e-12);
    }

    #[test]
    fn spin_turns_about_the_origin() {
        let m = Motion {
            spin_deg_per_s: 90.0,
            ..Default::default()
        };
        let p = m.offset_at(1.0).transform_point3(DVec3::X);
        assert!((p - DVec3::NEG_Z).length() < 1e-12, "{p}");
        assert_eq!(m.offset_at(0.0).transform_point3(DVec3::X), DVec3::X);
    }
}
