// Ray-primitive intersection and the two scene queries (closest hit, any hit), written as
// the CPU reference (crates/render-cpu) writes them so that both round alike. Rays hit on
// t in (T_MIN, t_max). The queries loop over the analytic shapes and traverse the triangle
// BVH (bvh_nodes); like the CPU's, its box tests are widened so that it finds exactly the
// hits of a loop over all triangles, and ties at the same t go to the lowest triangle id.

const T_MIN: f32 = 1e-4;
const EPS: f32 = 1e-4;
// "No hit": larger than any hit distance.
const NO_HIT: f32 = 3.0e38;

// A ray origin + t·dir; dir is near unit length but never renormalised.
struct Ray {
    origin: vec3<f32>,
    dir: vec3<f32>,
    inv_len2: f32,
}

fn make_ray(origin: vec3<f32>, dir: vec3<f32>) -> Ray {
    return Ray(origin, dir, 1.0 / dot(dir, dir));
}

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

// The ray's shear for the watertight triangle test of Woop, Benthin and Wald (JCGT 2013):
// its dominant axis kz becomes z and (sx, sy, sz) map its direction to +z.
struct Shear {
    kx: u32,
    ky: u32,
    kz: u32,
    s: vec3<f32>,
}

fn make_shear(d: vec3<f32>) -> Shear {
    let a = abs(d);
    var kz = 0u;
    var largest = a.x;
    if a.y > largest {
        largest = a.y;
        kz = 1u;
    }
    if a.z > largest {
        kz = 2u;
    }
    var kx = (kz + 1u) % 3u;
    var ky = (kx + 1u) % 3u;
    if d[kz] < 0.0 {
        let swap = kx;
        kx = ky;
        ky = swap;
    }
    return Shear(kx, ky, kz, vec3<f32>(d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]));
}

// p·q - r·s nearly exactly (Kahan's difference of products): the edge tie-break, where the
// CPU reference recomputes in f64.
fn diff_of_products(p: f32, q: f32, r: f32, s: f32) -> f32 {
    let w = r * s;
    let e = fma(-r, s, w);
    let f = fma(p, q, -w);
    return f + e;
}

// The watertight test: t of the hit of `tri` in (T_MIN, t_max), else NO_HIT.
fn hit_triangle(tri: Triangle, origin: vec3<f32>, sh: Shear, t_max: f32) -> f32 {
    let a = tri.v0 - origin;
    let b = tri.v1 - origin;
    let c = tri.v2 - origin;
    let ax = a[sh.kx] - sh.s.x * a[sh.kz];
    let ay = a[sh.ky] - sh.s.y * a[sh.kz];
    let bx = b[sh.kx] - sh.s.x * b[sh.kz];
    let by = b[sh.ky] - sh.s.y * b[sh.kz];
    let cx = c[sh.kx] - sh.s.x * c[sh.kz];
    let cy = c[sh.ky] - sh.s.y * c[sh.kz];
    var u = cx * by - cy * bx;
    var v = ax * cy - ay * cx;
    var w = bx * ay - by * ax;
    if u == 0.0 || v == 0.0 || w == 0.0 {
        u = diff_of_products(cx, by, cy, bx);
        v = diff_of_products(ax, cy, ay, cx);
        w = diff_of_products(bx, ay, by, ax);
    }
    if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
        return NO_HIT;
    }
    let det = u + v + w;
    if det == 0.0 {
        return NO_HIT;
    }
    let t_scaled = u * (sh.s.z * a[sh.kz]) + v * (sh.s.z * b[sh.kz]) + w * (sh.s.z * c[sh.kz]);
    let t = t_scaled / det;
    if t > T_MIN && t < t_max {
        return t;
    }
    return NO_HIT;
}

// The nearest hit: its distance (NO_HIT for a miss) and primitive id (shapes first, then
// triangles at shape_count + their leaf-order index).
struct Hit {
    t: f32,
    prim: u32,
}

// A BVH child reference: an inner node index, or LEAF_BIT | count << 27 | first.
const LEAF_BIT: u32 = 0x80000000u;
// Box tests widen the entry and exit distances by 2^-20 relative, as the CPU's do.
const BOX_NEAR_SCALE: f32 = 0.99999904632568359375;
const BOX_FAR_SCALE: f32 = 1.00000095367431640625;
// A box the ray misses has this entry distance (above NO_HIT).
const BOX_MISS: f32 = 3.4e38;

fn child_ref(first: u32, count: u32) -> u32 {
    return select(first, LEAF_BIT | (count << 27u) | first, count > 0u);
}

// A ray prepared for box tests. Zero direction components take no division: such a ray
// lies in that axis' slab for every t when its origin is inside it (bounds included), and
// for none otherwise.
struct BoxRay {
    origin: vec3<f32>,
    inv: vec3<f32>,
    flat: vec3<bool>,
}

fn make_box_ray(ray: Ray) -> BoxRay {
    let flat = ray.dir == vec3<f32>(0.0);
    return BoxRay(ray.origin, 1.0 / select(ray.dir, vec3<f32>(1.0), flat), flat);
}

// The widened entry distance of the box [lo, hi] when the ray meets it on [0, t_max],
// else BOX_MISS.
fn box_entry(lo: vec3<f32>, hi: vec3<f32>, br: BoxRay, t_max: f32) -> f32 {
    let a = (lo - br.origin) * br.inv;
    let b = (hi - br.origin) * br.inv;
    let inside = br.origin >= lo & br.origin <= hi;
    let t0 = select(min(a, b), select(vec3<f32>(BOX_MISS), vec3<f32>(-BOX_MISS), inside), br.flat);
    let t1 = select(max(a, b), select(vec3<f32>(-BOX_MISS), vec3<f32>(BOX_MISS), inside), br.flat);
    let near = max(max(t0.x, t0.y), max(t0.z, 0.0)) * BOX_NEAR_SCALE;
    let far = min(min(t1.x, t1.y), t1.z) * BOX_FAR_SCALE;
    return select(BOX_MISS, near, near <= min(far, t_max));
}

fn closest_hit(ray: Ray) -> Hit {
    var hit = Hit(NO_HIT, 0u);
    for (var i = 0u; i < frame.shape_count; i++) {
        let t = hit_shape(shapes[i], ray, hit.t);
        if t < hit.t {
            hit = Hit(t, i);
        }
    }
    if frame.triangle_count == 0u {
        return hit;
    }
    let sh = make_shear(ray.dir);
    let br = make_box_ray(ray);
    // The id of the best triangle so far; 0 lets no triangle tie a shape's hit.
    var best_id = 0u;
    var stack_ref: array<u32, BVH_STACK_SIZE>;
    var stack_t: array<f32, BVH_STACK_SIZE>;
    var sp = 0u;
    var cur = 0u;
    loop {
        if (cur & LEAF_BIT) == 0u {
            let node = bvh_nodes[cur];
            let tl = box_entry(node.left_min, node.left_max, br, hit.t);
            let tr = box_entry(node.right_min, node.right_max, br, hit.t);
            let rl = child_ref(node.left_first, node.left_count);
            let rr = child_ref(node.right_first, node.right_count);
            if tl != BOX_MISS && tr != BOX_MISS {
                // Nearer child first; the other waits on the stack with its entry distance.
                let left_first = tl <= tr;
                stack_ref[sp] = select(rl, rr, left_first);
                stack_t[sp] = select(tl, tr, left_first);
                sp++;
                cur = select(rr, rl, left_first);
                continue;
            }
            if tl != BOX_MISS {
                cur = rl;
                continue;
            }
            if tr != BOX_MISS {
                cur = rr;
                continue;
            }
        } else {
            let first = cur & 0x07ffffffu;
            let end = first + ((cur >> 27u) & 0xfu);
            for (var k = first; k < end; k++) {
                let tri = triangles[k];
                let t = hit_triangle(tri, ray.origin, sh, NO_HIT);
                if t < hit.t || (t == hit.t && tri.id < best_id) {
                    hit = Hit(t, frame.shape_count + k);
                    best_id = tri.id;
                }
            }
        }
        // Pop the next pending child that can still hold a closer hit.
        var found = false;
        while sp > 0u {
            sp--;
            if stack_t[sp] <= hit.t {
                cur = stack_ref[sp];
                found = true;
                break;
            }
        }
        if !found {
            break;
        }
    }
    return hit;
}

// Whether anything is hit on t in (T_MIN, t_max).
fn occluded(ray: Ray, t_max: f32) -> bool {
    for (var i = 0u; i < frame.shape_count; i++) {
        if hit_shape(shapes[i], ray, t_max) < t_max {
            return true;
        }
    }
    if frame.triangle_count == 0u {
        return false;
    }
    let sh = make_shear(ray.dir);
    let br = make_box_ray(ray);
    var stack_ref: array<u32, BVH_STACK_SIZE>;
    var sp = 0u;
    var cur = 0u;
    loop {
        if (cur & LEAF_BIT) == 0u {
            let node = bvh_nodes[cur];
            let hit_l = box_entry(node.left_min, node.left_max, br, t_max) != BOX_MISS;
            let hit_r = box_entry(node.right_min, node.right_max, br, t_max) != BOX_MISS;
            let rl = child_ref(node.left_first, node.left_count);
            let rr = child_ref(node.right_first, node.right_count);
            if hit_l && hit_r {
                stack_ref[sp] = rr;
                sp++;
                cur = rl;
                continue;
            }
            if hit_l {
                cur = rl;
                continue;
            }
            if hit_r {
                cur = rr;
                continue;
            }
        } else {
            let first = cur & 0x07ffffffu;
            let end = first + ((cur >> 27u) & 0xfu);
            for (var k = first; k < end; k++) {
                if hit_triangle(triangles[k], ray.origin, sh, t_max) < t_max {
                    return true;
                }
            }
        }
        if sp == 0u {
            return false;
        }
        sp--;
        cur = stack_ref[sp];
    }
    return false;
}

// What shading needs of a hit point p on primitive `prim`.
struct Surface {
    // The geometric normal as the primitive defines it (not yet flipped toward the ray).
    normal: vec3<f32>,
    material: u32,
}

fn surface_at(prim: u32, p: vec3<f32>) -> Surface {
    if prim >= frame.shape_count {
        let tri = triangles[prim - frame.shape_count];
        return Surface(tri.normal, tri.material);
    }
    let s = shapes[prim];
    if s.kind == SHAPE_SPHERE {
        return Surface((p - s.p0) * s.s1, s.material);
    }
    return Surface(s.p1, s.material);
}

fn checker_parity(u: f32, v: f32, w: f32, size: f32) -> bool {
    let cell = i32(floor(u / size)) + i32(floor(v / size)) + i32(floor(w / size));
    return (cell & 1) != 0;
}

// The albedo of diffuse material `m` at p on primitive `prim` (docs/shading.md, Checker).
fn diffuse_albedo(m: Material, prim: u32, p: vec3<f32>) -> vec3<f32> {
    if m.checker_size <= 0.0 {
        return m.colour;
    }
    var odd: bool;
    // Meshes use the 3D checker, as spheres do.
    var kind = SHAPE_SPHERE;
    if prim < frame.shape_count {
        kind = shapes[prim].kind;
    }
    if kind == SHAPE_QUAD {
        let s = shapes[prim];
        let rel = p - s.p0;
        odd = checker_parity(dot(rel, s.p2) * s.s0, dot(rel, s.p3) * s.s1, 0.0, m.checker_size);
    } else if kind == SHAPE_PLANE {
        let s = shapes[prim];
        let rel = p - s.p0;
        odd = checker_parity(dot(rel, s.p2), dot(rel, s.p3), 0.0, m.checker_size);
    } else {
        odd = checker_parity(p.x, p.y, p.z, m.checker_size);
    }
    return select(m.colour, m.colour_b, odd);
}
