//! How each surface of a moving world moved between two frames: what the temporal mode
//! (`docs/temporal.md`, "Moving objects") reprojects a point of a moving object by. Computed
//! once per frame on the host, the same numbers for both backends.

use crate::two_level::SceneLayout;
use glam::{DAffine3, DMat3, DVec3};
use steadyray_scene::{Pose, Scene};

/// How one surface (a surface id of [`SceneLayout`]) moved from the previous frame to this
/// one.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum SurfaceMove {
    /// It is where it was (or does not exist now).
    #[default]
    Still,
    /// It moved: the map takes its points and normals from this frame back to the previous.
    Moved(MoveMap),
    /// It did not exist in the previous frame (or cannot be mapped back): no history.
    New,
}

/// An affine map of points, with the map of normals that goes with it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MoveMap {
    /// Rows (x, y, z, translation): p' = (r_i.x·p.x + r_i.y·p.y + r_i.z·p.z + r_i.w), left
    /// to right.
    pub point_rows: [[f32; 4]; 3],
    /// Rows of the cofactor matrix of the linear part: n' = normalize(r_i · n).
    pub normal_rows: [[f32; 3]; 3],
}

impl MoveMap {
    /// The map of `p`.
    #[inline]
    pub fn point(&self, p: [f32; 3]) -> [f32; 3] {
        self.point_rows
            .map(|r| r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + r[3])
    }

    /// The map of unit normal `n`: m = (r_0·n, r_1·n, r_2·n), then m · (1 / sqrt(m·m)).
    #[inline]
    pub fn normal(&self, n: [f32; 3]) -> [f32; 3] {
        let m = self
            .normal_rows
            .map(|r| r[0] * n[0] + r[1] * n[1] + r[2] * n[2]);
        let inv = 1.0 / (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
        m.map(|c| c * inv)
    }
}

/// Where an object's copy puts its model space at a time: a sphere's centre and radius as a
/// scaled frame, a quad's corner and edges (and their cross product), a mesh copy's map.
fn frames(pose: &Pose<'_>) -> Vec<DAffine3> {
    match pose {
        Pose::Sphere { center, radius } => vec![DAffine3::from_scale_rotation_translation(
            DVec3::splat(f64::from(*radius)),
            glam::DQuat::IDENTITY,
            DVec3::from(*center),
        )],
        Pose::Quad {
            corner,
            edge_u,
            edge_v,
        } => {
            let (u, v) = (DVec3::from(*edge_u), DVec3::from(*edge_v));
            vec![DAffine3 {
                matrix3: DMat3::from_cols(u, v, u.cross(v)),
                translation: DVec3::from(*corner),
            }]
        }
        Pose::Plane { .. } => vec![DAffine3::IDENTITY],
        Pose::Mesh { copies, .. } => copies.clone(),
    }
}

/// The move of a surface placed by `now` that was placed by `before`.
fn move_of(before: &DAffine3, now: &DAffine3) -> SurfaceMove {
    if before == now {
        return SurfaceMove::Still;
    }
    let det = now.matrix3.determinant();
    if !(det.is_finite() && det.abs() > 1e-30) {
        return SurfaceMove::New;
    }
    let map = *before * now.inverse();
    let cofactor = map.matrix3.inverse().transpose() * map.matrix3.determinant();
    let point_rows = [0, 1, 2].map(|i| {
        let r = map.matrix3.row(i).as_vec3();
        [r.x, r.y, r.z, map.translation[i] as f32]
    });
    let normal_rows = [0, 1, 2].map(|i| cofactor.row(i).as_vec3().to_array());
    let finite = point_rows.iter().flatten().all(|v| v.is_finite())
        && normal_rows.iter().flatten().all(|v| v.is_finite());
    if finite {
        SurfaceMove::Moved(MoveMap {
            point_rows,
            normal_rows,
        })
    } else {
        SurfaceMove::New
    }
}

/// Every surface's move from scene time `before_s` to `now_s`, by surface id, into `out`
/// (cleared first; one entry per id of `layout`).
pub fn surface_moves(
    scene: &Scene,
    layout: &SceneLayout,
    before_s: f64,
    now_s: f64,
    out: &mut Vec<SurfaceMove>,
) {
    out.clear();
    for obj in &scene.objects {
        let copies = match &obj.shape {
            steadyray_scene::Shape::Mesh { instances, .. } => instances.len().max(1),
            _ => 1,
        };
        let moves = match (obj.pose_at(before_s), obj.pose_at(now_s)) {
            (_, None) => vec![SurfaceMove::Still; copies],
            (None, Some(_)) => vec![SurfaceMove::New; copies],
            (Some(before), Some(now)) => frames(&before)
                .iter()
                .zip(&frames(&now))
                .map(|(b, n)| move_of(b, n))
                .collect(),
        };
        out.extend(moves);
    }
    debug_assert_eq!(out.len() as u32, layout.surface_count());
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_scene::scene_of as scene;
    use glam::Vec3;
    use steadyray_scene::{Motion, MotionKey, Object, Shape};

    fn sliding(shape: Shape, visible: Option<Vec<[f64; 2]>>) -> Object {
        Object {
            motion: Some(Motion {
                keys: vec![
                    MotionKey {
                        t: 0.0,
                        translate: Some(Vec3::ZERO),
                        rotate_y_deg: Some(0.0),
                        scale: None,
                    },
                    MotionKey {
                        t: 1.0,
                        translate: Some(Vec3::new(2.0, 0.0, 0.0)),
                        rotate_y_deg: Some(90.0),
                        scale: None,
                    },
                ],
                visible,
                ..Default::default()
            }),
            ..Object::fixed("o", shape, 0)
        }
    }

    #[test]
    fn moving_points_map_back_to_where_they_were() {
        let ball = Shape::Sphere {
            center: Vec3::new(0.0, 1.0, -4.0),
            radius: 0.5,
        };
        let quad = Shape::Quad {
            corner: Vec3::new(-1.0, 0.0, -6.0),
            edge_u: Vec3::X,
            edge_v: Vec3::Y,
        };
        let still = Object::fixed(
            "floor",
            Shape::Plane {
                point: Vec3::ZERO,
                normal: Vec3::Y,
            },
            0,
        );
        let s = scene(vec![
            sliding(ball.clone(), None),
            sliding(quad, None),
            still,
            sliding(ball, Some(vec![[0.5, 2.0]])),
        ]);
        let layout = SceneLayout::new(&s).unwrap();
        let mut moves = Vec::new();
        surface_moves(&s, &layout, 0.25, 0.75, &mut moves);
        assert_eq!(moves.len(), 4);
        assert_eq!(moves[2], SurfaceMove::Still);
        assert_eq!(moves[3], SurfaceMove::New, "not there at 0.25");
        let pose = |i: usize, t: f64| s.objects[i].pose_at(t).unwrap();
        let (Pose::Sphere { center: c0, .. }, Pose::Sphere { center: c1, .. }) =
            (pose(0, 0.25), pose(0, 0.75))
        else {
            panic!("spheres");
        };
        let SurfaceMove::Moved(ball) = moves[0] else {
            panic!("the ball moved: {:?}", moves[0]);
        };
        let top = ball.point((c1 + Vec3::Y * 0.5).to_array());
        assert!((Vec3::from(top) - (c0 + Vec3::Y * 0.5)).length() < 1e-5);
        // The quad turned by 45 degrees: a point on it maps onto the old quad, its normal
        // onto the old normal.
        let SurfaceMove::Moved(quad) = moves[1] else {
            panic!("the quad moved");
        };
        let (
            Pose::Quad {
                corner: a0,
                edge_u: u0,
                edge_v: v0,
            },
            Pose::Quad {
                corner: a1,
                edge_u: u1,
                edge_v: v1,
            },
        ) = (pose(1, 0.25), pose(1, 0.75))
        else {
            panic!("quads");
        };
        let p = quad.point((a1 + 0.3 * u1 + 0.6 * v1).to_array());
        assert!((Vec3::from(p) - (a0 + 0.3 * u0 + 0.6 * v0)).length() < 1e-5);
        let n = quad.normal(u1.cross(v1).normalize().to_array());
        assert!((Vec3::from(n) - u0.cross(v0).normalize()).length() < 1e-5);
        // At the same time nothing moves.
        surface_moves(&s, &layout, 0.75, 0.75, &mut moves);
        assert!(moves.iter().all(|m| *m == SurfaceMove::Still));
    }
}
