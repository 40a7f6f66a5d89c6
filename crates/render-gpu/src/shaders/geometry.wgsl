// Ray-shape intersection and what shading reads of a hit, written as the CPU reference
// (crates/render-cpu) writes them so that both round alike. Rays hit on t in
// (T_MIN, t_max). The scene queries over the two-level BVH are in top_level.wgsl.

// Offset of secondary ray origins along the normal.
const EPS: f32 = 1e-4;

fn copysign(magnitude: f32, sign: f32) -> f32 {
    return bitcast<f32>((bitcast<u32>(magnitude) & 0x7fffffffu) | (bitcast<u32>(sign) & 0x80000000u));
}

// The sphere test of "Precision Improvements for Ray/Sphere Intersection" (Ray Tracing Gems,
// ch. 7): the discriminant from the distance to the ray's line, the roots as q/a and c/q.
fn hit_sphere(s: Shape, ray: Ray, t_max: f32) -> f32 {
    let f = ray.origin - s.p0;
    let half_b = dot(f, ray.dir);
    let off_axis = f - (half_b * ray.inv_len2) * ray.dir;
    let disc = (s.s0 - dot(off_axis, off_axis)) / ray.inv_len2;
    if disc < 0.0 {
        return NO_HIT;
    }
    let c = dot(f, f) - s.s0;
    let q = -(half_b + copysign(sqrt(disc), half_b));
    let r0 = q * ray.inv_len2;
    let r1 = c / q;
    let ordered = r0 <= r1;
    let near = select(r1, r0, ordered);
    let far = select(r0, r1, ordered);
    if near > T_MIN && near < t_max {
        return near;
    }
    if far > T_MIN && far < t_max {
        return far;
    }
    return NO_HIT;
}

// t of the hit of shape `s` in (T_MIN, t_max), else NO_HIT.
fn hit_shape(s: Shape, ray: Ray, t_max: f32) -> f32 {
    if s.kind == SHAPE_SPHERE {
        return hit_sphere(s, ray, t_max);
    }
    // Quad and plane: the supporting plane first (a zero denominator gives inf or NaN,
    // which fails the range test).
    let t = dot(s.p0 - ray.origin, s.p1) / dot(ray.dir, s.p1);
    if !(t > T_MIN && t < t_max) {
        return NO_HIT;
    }
    if s.kind == SHAPE_QUAD {
        let rel = ray.origin + t * ray.dir - s.p0;
        let a = dot(rel, s.p2);
        let b = dot(rel, s.p3);
        if !(a >= 0.0 && a <= 1.0 && b >= 0.0 && b <= 1.0) {
            return NO_HIT;
        }
    }
    return t;
}

// The nearest hit: its distance (NO_HIT for a miss), its primitive (a shape's index in
// `shapes`, or for a mesh the triangle's position in `triangles`) and its instance
// (NO_INSTANCE for a shape).
struct Hit {
    t: f32,
    prim: u32,
    inst: u32,
}

// What shading needs of a hit point p on primitive `prim`.
struct Surface {
    // The geometric normal as the primitive defines it (not yet flipped toward the ray).
    normal: vec3<f32>,
    material: u32,
}

fn surface_at(hit: Hit, p: vec3<f32>) -> Surface {
    if hit.inst != NO_INSTANCE {
        let inst = instances[hit.inst];
        return Surface(normal_to_world(inst, triangles[hit.prim].normal), inst.material);
    }
    let s = shapes[hit.prim];
    if s.kind == SHAPE_SPHERE {
        return Surface((p - s.p0) * s.s1, s.material);
    }
    return Surface(s.p1, s.material);
}

fn checker_parity(u: f32, v: f32, w: f32, size: f32) -> bool {
    let cell = i32(floor(u / size)) + i32(floor(v / size)) + i32(floor(w / size));
    return (cell & 1) != 0;
}

// The albedo of diffuse material `m` at p on the primitive of `hit` (docs/shading.md,
// Checker).
fn diffuse_albedo(m: Material, hit: Hit, p: vec3<f32>) -> vec3<f32> {
    if m.checker_size <= 0.0 {
        return m.colour;
    }
    var odd: bool;
    // Meshes use the 3D checker, as spheres do.
    var kind = SHAPE_SPHERE;
    if hit.inst == NO_INSTANCE {
        kind = shapes[hit.prim].kind;
    }
    if kind == SHAPE_QUAD {
        let s = shapes[hit.prim];
        let rel = p - s.p0;
        odd = checker_parity(dot(rel, s.p2) * s.s0, dot(rel, s.p3) * s.s1, 0.0, m.checker_size);
    } else if kind == SHAPE_PLANE {
        let s = shapes[hit.prim];
        let rel = p - s.p0;
        odd = checker_parity(dot(rel, s.p2), dot(rel, s.p3), 0.0, m.checker_size);
    } else {
        odd = checker_parity(p.x, p.y, p.z, m.checker_size);
    }
    return select(m.colour, m.colour_b, odd);
}
