//! Objects at a moment of scene time: where each shape is in the world then, and whether it
//! exists, from its placement, instances and [`crate::Motion`]. Renderers place their
//! primitives from this every frame.

use crate::{Object, Shape, Transform, TriangleMesh};
use glam::{DAffine3, DVec3, Vec3};

/// An object's shape at one moment, in world space.
#[derive(Clone, Debug, PartialEq)]
pub enum Pose<'a> {
    /// A sphere where its motion puts it.
    Sphere {
        /// World-space centre.
        center: Vec3,
        /// Radius, metres.
        radius: f32,
    },
    /// A parallelogram, as [`Shape::Quad`].
    Quad {
        /// World-space corner.
        corner: Vec3,
        /// First edge from `corner`.
        edge_u: Vec3,
        /// Second edge from `corner`.
        edge_v: Vec3,
    },
    /// An infinite plane, as [`Shape::Plane`].
    Plane {
        /// A world-space point on the plane.
        point: Vec3,
        /// Unit normal.
        normal: Vec3,
    },
    /// The mesh in model space and, per copy, the map from model space to the world.
    Mesh {
        /// The shape's mesh, unchanged.
        mesh: &'a TriangleMesh,
        /// Model space to world, one per copy (one per instance, or a single one).
        copies: Vec<DAffine3>,
    },
}

impl Object {
    /// The map taking the object's points as its shape places them (no motion) to where
    /// they are at scene time `t_s`: O + offset(t)·(x − O) about its placement origin O (a
    /// sphere's centre, a quad's corner, a mesh's `translate`; the identity without motion),
    /// or `None` when it does not exist then. What a point on it moved by between two times.
    pub fn placement_at(&self, t_s: f64) -> Option<DAffine3> {
        let Some(motion) = &self.motion else {
            return Some(DAffine3::IDENTITY);
        };
        if !motion.is_visible(t_s) {
            return None;
        }
        let origin = DVec3::from(match &self.shape {
            &Shape::Sphere { center, .. } => center,
            &Shape::Quad { corner, .. } => corner,
            &Shape::Plane { point, .. } => point,
            Shape::Mesh { placement, .. } => placement.translate,
        });
        Some(
            DAffine3::from_translation(origin)
                * motion.offset_at(t_s)
                * DAffine3::from_translation(-origin),
        )
    }

    /// The object at scene time `t_s`, or `None` when it does not exist then. An object
    /// without motion is where its shape says, at every time.
    pub fn pose_at(&self, t_s: f64) -> Option<Pose<'_>> {
        let motion = match &self.motion {
            Some(m) if !m.is_visible(t_s) => return None,
            Some(m) => m.offset_at(t_s),
            None => DAffine3::IDENTITY,
        };
        let moved = self.motion.is_some();
        // The origin and the motion's translation, added once in f64.
        let origin = |o: Vec3| (DVec3::from(o) + motion.translation).as_vec3();
        Some(match &self.shape {
            &Shape::Sphere { center, radius } if moved => Pose::Sphere {
                center: origin(center),
                radius: (f64::from(radius) * motion.matrix3.x_axis.length()) as f32,
            },
            &Shape::Sphere { center, radius } => Pose::Sphere { center, radius },
            &Shape::Quad {
                corner,
                edge_u,
                edge_v,
            } if moved => Pose::Quad {
                corner: origin(corner),
                edge_u: (motion.matrix3 * DVec3::from(edge_u)).as_vec3(),
                edge_v: (motion.matrix3 * DVec3::from(edge_v)).as_vec3(),
            },
            &Shape::Quad {
                corner,
                edge_u,
                edge_v,
            } => Pose::Quad {
                corner,
                edge_u,
                edge_v,
            },
            // Planes never move (the format refuses motion on them).
            &Shape::Plane { point, normal } => Pose::Plane { point, normal },
            Shape::Mesh {
                mesh,
                placement,
                instances,
            } => {
                let to_origin = DAffine3::from_translation(placement.translate.into());
                let outer = to_origin * motion;
                let linear = placement.linear();
                let copies = if instances.is_empty() {
                    vec![outer * linear]
                } else {
                    instances
                        .iter()
                        .map(|i: &Transform| outer * i.to_affine() * linear)
                        .collect()
                };
                Pose::Mesh { mesh, copies }
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Motion, MotionKey};

    fn moving(shape: Shape, motion: Motion) -> Object {
        Object {
            motion: Some(motion),
            ..Object::fixed("o", shape, 0)
        }
    }

    fn slide() -> Motion {
        Motion {
            keys: vec![
                MotionKey {
                    t: 0.0,
                    translate: Some(Vec3::ZERO),
                    rotate_y_deg: Some(0.0),
                    scale: Some(Vec3::ONE),
                },
                MotionKey {
                    t: 1.0,
                    translate: Some(Vec3::new(2.0, 0.0, 0.0)),
                    rotate_y_deg: Some(90.0),
                    scale: Some(Vec3::splat(2.0)),
                },
            ],
            ..Default::default()
        }
    }

    #[test]
    fn a_point_on_an_object_follows_its_placement() {
        let ball = moving(
            Shape::Sphere {
                center: Vec3::new(0.0, 1.0, 0.0),
                radius: 0.5,
            },
            slide(),
        );
        // The top of the ball at rest; at t = 1 the ball has moved 2 along x, turned 90°
        // and doubled: its top is 1 above the new centre.
        let top = DVec3::new(0.0, 1.5, 0.0);
        let moved = ball.placement_at(1.0).unwrap().transform_point3(top);
        assert!(
            (moved - DVec3::new(2.0, 2.0, 0.0)).length() < 1e-9,
            "{moved}"
        );
        let fixed = Object::fixed(
            "f",
            Shape::Sphere {
                center: Vec3::ZERO,
                radius: 1.0,
            },
            0,
        );
        assert_eq!(fixed.placement_at(5.0), Some(DAffine3::IDENTITY));
        let hidden = moving(
            Shape::Sphere {
                center: Vec3::ZERO,
                radius: 1.0,
            },
            Motion {
                visible: Some(vec![[0.0, 1.0]]),
                ..Default::default()
            },
        );
        assert!(hidden.placement_at(0.5).is_some());
        assert_eq!(hidden.placement_at(2.0), None);
    }

    #[test]
    fn spheres_and_quads_move_about_their_origin() {
        let ball = moving(
            Shape::Sphere {
                center: Vec3::new(0.0, 1.0, 0.0),
                radius: 0.5,
            },
            slide(),
        );
        assert_eq!(
            ball.pose_at(1.0),
            Some(Pose::Sphere {
                center: Vec3::new(2.0, 1.0, 0.0),
                radius: 1.0
            })
        );
        let quad = moving(
            Shape::Quad {
                corner: Vec3::new(1.0, 0.0, 0.0),
                edge_u: Vec3::X,
                edge_v: Vec3::Y,
            },
            slide(),
        );
        let Some(Pose::Quad {
            corner,
            edge_u,
            edge_v,
        }) = quad.pose_at(1.0)
        else {
            panic!("a quad");
        };
        assert_eq!(corner, Vec3::new(3.0, 0.0, 0.0));
        assert!(
            (edge_u - Vec3::new(0.0, 0.0, -2.0)).length() < 1e-6,
            "{edge_u}"
        );
        assert!(
            (edge_v - Vec3::new(0.0, 2.0, 0.0)).length() < 1e-6,
            "{edge_v}"
        );
    }

    #[test]
    fn instances_sit_about_the_placement_origin() {
        let mesh = TriangleMesh {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            triangles: vec![[0, 1, 2]],
        };
        let placement = Transform {
            translate: Vec3::new(10.0, 0.0, 0.0),
            scale: Vec3::splat(2.0),
            rotate_y_deg: 0.0,
        };
        let shape = Shape::Mesh {
            mesh,
            placement,
            instances: vec![
                Transform::IDENTITY,
                Transform {
                    translate: Vec3::new(0.0, 0.0, 5.0),
                    rotate_y_deg: 90.0,
                    ..Transform::IDENTITY
                },
            ],
        };
        let still = Object::fixed("m", shape.clone(), 0);
        let Some(Pose::Mesh { copies, .. }) = still.pose_at(3.0) else {
            panic!("a mesh");
        };
        let p = |i: usize, v: Vec3| copies[i].transform_point3(v.into()).as_vec3();
        assert_eq!(p(0, Vec3::X), Vec3::new(12.0, 0.0, 0.0));
        // Scaled by the placement to (2, 0, 0), turned to (0, 0, -2), moved by (0, 0, 5),
        // then to the placement's origin.
        assert!((p(1, Vec3::X) - Vec3::new(10.0, 0.0, 3.0)).length() < 1e-5);
        // Invisible objects have no pose.
        let hidden = moving(
            shape,
            Motion {
                visible: Some(vec![[1.0, 2.0]]),
                ..Default::default()
            },
        );
        assert!(hidden.pose_at(0.5).is_none());
        assert!(hidden.pose_at(1.5).is_some());
    }
}
