//! Triangles: the watertight ray-triangle test of Woop, Benthin and Wald, "Watertight
//! Ray/Triangle Intersection", JCGT 2(1), 2013.

use crate::ray::{Ray, T_MIN};
use glam::{Vec3, Vec3A};

/// One triangle with its outward normal normalize(cross(b - a, c - a)).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Triangle {
    pub v: [Vec3; 3],
    pub normal: Vec3A,
    pub material: u32,
}

impl Triangle {
    /// Prepares triangle (a, b, c); `None` when it has no area.
    pub fn new(v: [Vec3; 3], material: u32) -> Option<Self> {
        let n = (v[1] - v[0]).cross(v[2] - v[0]);
        let len2 = n.length_squared();
        (len2 > 0.0 && len2.is_finite()).then(|| Self {
            v,
            normal: Vec3A::from(n.normalize()),
            material,
        })
    }
}

/// A ray transformed for the watertight test: its dominant axis becomes z and the shear
/// (sx, sy, sz) maps its direction to +z.
#[derive(Clone, Copy, Debug)]
pub(crate) struct WatertightRay {
    origin: Vec3,
    kx: usize,
    ky: usize,
    kz: usize,
    sx: f32,
    sy: f32,
    sz: f32,
}

impl WatertightRay {
    /// The shear for `ray`, computed once per ray and shared by all its triangle tests.
    pub fn new(ray: &Ray) -> Self {
        let d = Vec3::from(ray.dir);
        let kz = d.abs().max_position();
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        if d[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        Self {
            origin: ray.origin.into(),
            kx,
            ky,
            kz,
            sx: d[kx] / d[kz],
            sy: d[ky] / d[kz],
            sz: 1.0 / d[kz],
        }
    }

    /// The t in (T_MIN, t_max) where the ray meets `tri`. Edges shared by two triangles are
    /// hit by exactly one of them or both, never neither.
    #[inline]
    pub fn intersect(&self, tri: &Triangle, t_max: f32) -> Option<f32> {
        let (kx, ky, kz) = (self.kx, self.ky, self.kz);
        let a = tri.v[0] - self.origin;
        let b = tri.v[1] - self.origin;
        let c = tri.v[2] - self.origin;
        let ax = a[kx] - self.sx * a[kz];
        let ay = a[ky] - self.sy * a[kz];
        let bx = b[kx] - self.sx * b[kz];
        let by = b[ky] - self.sy * b[kz];
        let cx = c[kx] - self.sx * c[kz];
        let cy = c[ky] - self.sy * c[kz];
        let mut u = cx * by - cy * bx;
        let mut v = ax * cy - ay * cx;
        let mut w = bx * ay - by * ax;
        if u == 0.0 || v == 0.0 || w == 0.0 {
            // On an edge in f32: decide in f64, as the paper does.
            let f =
                |p: f32, q: f32, r: f32, s: f32| (p as f64 * q as f64 - r as f64 * s as f64) as f32;
            u = f(cx, by, cy, bx);
            v = f(ax, cy, ay, cx);
            w = f(bx, ay, by, ax);
        }
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            return None;
        }
        let det = u + v + w;
        if det == 0.0 {
            return None;
        }
        let t_scaled = u * (self.sz * a[kz]) + v * (self.sz * b[kz]) + w * (self.sz * c[kz]);
        let t = t_scaled / det;
        (t > T_MIN && t < t_max).then_some(t)
    }
}

/// All triangles of the scene behind a closest-hit / any-hit interface. The queries are
/// brute force for now; a BVH replaces their insides without changing their callers.
#[derive(Clone, Debug, Default)]
pub(crate) struct Triangles {
    tris: Vec<Triangle>,
}

impl Triangles {
    /// Adds a triangle.
    pub fn push(&mut self, tri: Triangle) {
        self.tris.push(tri);
    }

    /// Triangle `i`.
    #[inline]
    pub fn get(&self, i: u32) -> &Triangle {
        &self.tris[i as usize]
    }

    /// The nearest hit in (T_MIN, t_max): its t and triangle index.
    #[inline]
    pub fn closest(&self, ray: &Ray, mut t_max: f32) -> Option<(f32, u32)> {
        if self.tris.is_empty() {
            return None;
        }
        let wr = WatertightRay::new(ray);
        let mut best = None;
        for (i, tri) in self.tris.iter().enumerate() {
            if let Some(t) = wr.intersect(tri, t_max) {
                t_max = t;
                best = Some((t, i as u32));
            }
        }
        best
    }

    /// Whether any triangle is hit on t in (T_MIN, t_max).
    #[inline]
    pub fn any_hit(&self, ray: &Ray, t_max: f32) -> bool {
        if self.tris.is_empty() {
            return false;
        }
        let wr = WatertightRay::new(ray);
        self.tris
            .iter()
            .any(|tri| wr.intersect(tri, t_max).is_some())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri(a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> Triangle {
        Triangle::new([a.into(), b.into(), c.into()], 0).unwrap()
    }

    #[test]
    fn hits_both_windings_and_reports_t() {
        let t1 = tri([-1.0, -1.0, -3.0], [1.0, -1.0, -3.0], [0.0, 1.0, -3.0]);
        let t2 = tri([-1.0, -1.0, -3.0], [0.0, 1.0, -3.0], [1.0, -1.0, -3.0]);
        let ray = Ray::new(Vec3A::ZERO, Vec3A::NEG_Z);
        let wr = WatertightRay::new(&ray);
        assert_eq!(wr.intersect(&t1, f32::INFINITY), Some(3.0));
        assert_eq!(wr.intersect(&t2, f32::INFINITY), Some(3.0));
        assert_eq!(t1.normal, Vec3A::Z);
        assert_eq!(t2.normal, Vec3A::NEG_Z);
        assert_eq!(wr.intersect(&t1, 2.0), None);
        let miss = Ray::new(Vec3A::new(2.0, 0.0, 0.0), Vec3A::NEG_Z);
        assert_eq!(
            WatertightRay::new(&miss).intersect(&t1, f32::INFINITY),
            None
        );
    }

    #[test]
    fn shared_edges_are_watertight() {
        // Two triangles sharing the diagonal of a skewed quad; rays sweep across it.
        let a = Vec3::new(-1.3, -0.7, -4.1);
        let b = Vec3::new(1.1, -0.9, -3.7);
        let c = Vec3::new(1.2, 1.05, -4.4);
        let d = Vec3::new(-0.8, 0.9, -4.0);
        let mut set = Triangles::default();
        set.push(Triangle::new([a, b, c], 0).unwrap());
        set.push(Triangle::new([a, c, d], 0).unwrap());
        let origin = Vec3A::new(0.013, -0.021, 0.37);
        for i in 0..=2000 {
            let s = i as f32 / 2000.0;
            // points on the shared edge a-c (and a hair off either side)
            for off in [-1e-7f32, 0.0, 1e-7] {
                let target = Vec3A::from(a.lerp(c, 0.05 + 0.9 * s)) + Vec3A::splat(off);
                let ray = Ray::new(origin, (target - origin).normalize());
                assert!(set.closest(&ray, f32::INFINITY).is_some(), "leak at s={s}");
                assert!(set.any_hit(&ray, f32::INFINITY));
            }
        }
    }

    #[test]
    fn degenerate_triangles_are_refused() {
        assert!(Triangle::new([Vec3::ZERO, Vec3::X, Vec3::X * 3.0], 0).is_none());
    }
}
