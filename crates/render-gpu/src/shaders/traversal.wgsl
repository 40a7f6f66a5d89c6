// Ray queries against the triangle mesh, shared by the integrator (geometry.wgsl) and the ray
// caster (raycast.wgsl): the watertight ray-triangle test, written as steadyray-accel writes
// it on the CPU so that both round alike, and the traversal of the 4-wide BVH.
// Like the CPU's, the box tests are widened so that the traversal finds exactly the hits of
// a loop over all triangles, and ties at the same t go to the lowest triangle id.
//
// The including module declares `triangles: array<Triangle>` and `bvh_nodes: array<BvhNode>`,
// which may hold several meshes one after another: a query names where its mesh's nodes
// (its root first) and triangles (in its BVH's leaf order) start. Callers skip the queries
// for meshes without triangles.

// Rays hit on t in (T_MIN, t_max).
const T_MIN: f32 = 1e-4;
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

// Box tests widen the entry and exit distances by 2^-20 relative, as the CPU's do.
const BOX_NEAR_SCALE: f32 = 0.99999904632568359375;
const BOX_FAR_SCALE: f32 = 1.00000095367431640625;
// A box the ray misses has this entry distance (above NO_HIT).
const BOX_MISS: f32 = 3.4e38;

// The triangles of leaf entry `leaf` (BVH_LEAF | count << 27 | first): positions [x, y).
fn leaf_range(leaf: u32) -> vec2<u32> {
    let first = leaf & 0x07ffffffu;
    return vec2<u32>(first, first + ((leaf >> 27u) & 0xfu));
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

// Per lane, the distances at which the ray enters and leaves one axis' slabs.
struct Slabs {
    enter: vec4<f32>,
    leave: vec4<f32>,
}

fn slabs(lo: vec4<f32>, hi: vec4<f32>, origin: f32, inv: f32, flat: bool) -> Slabs {
    let o = vec4<f32>(origin);
    let a = (lo - o) * inv;
    let b = (hi - o) * inv;
    let inside = o >= lo & o <= hi;
    let enter = select(vec4<f32>(BOX_MISS), vec4<f32>(-BOX_MISS), inside);
    let leave = select(vec4<f32>(-BOX_MISS), vec4<f32>(BOX_MISS), inside);
    return Slabs(select(min(a, b), enter, flat), select(max(a, b), leave, flat));
}

// A node's children in the order to visit them: by widened entry distance, nearest first,
// the boxes the ray misses on [0, t_max] (and unused lanes) last at BOX_MISS.
struct Children {
    entry: vec4<f32>,
    child: vec4<u32>,
}

// Two compare-exchanges at once: (a.x, b.x) and (a.y, b.y) each become (nearer, farther).
struct SortedPairs {
    near_entry: vec2<f32>,
    near_child: vec2<u32>,
    far_entry: vec2<f32>,
    far_child: vec2<u32>,
}

fn sort_pairs(a: vec2<f32>, ca: vec2<u32>, b: vec2<f32>, cb: vec2<u32>) -> SortedPairs {
    let swap = b < a;
    return SortedPairs(
        select(a, b, swap),
        select(ca, cb, swap),
        select(b, a, swap),
        select(cb, ca, swap),
    );
}

fn ordered_children(node: BvhNode, br: BoxRay, t_max: f32) -> Children {
    let x = slabs(node.min_x, node.max_x, br.origin.x, br.inv.x, br.flat.x);
    let y = slabs(node.min_y, node.max_y, br.origin.y, br.inv.y, br.flat.y);
    let z = slabs(node.min_z, node.max_z, br.origin.z, br.inv.z, br.flat.z);
    let near = max(max(x.enter, y.enter), max(z.enter, vec4<f32>(0.0))) * BOX_NEAR_SCALE;
    let far = min(min(x.leave, y.leave), z.leave) * BOX_FAR_SCALE;
    let hit = near <= min(far, vec4<f32>(t_max)) & node.child != vec4<u32>(BVH_EMPTY);
    let d = select(vec4<f32>(BOX_MISS), near, hit);
    let c = node.child;
    // The four-lane sorting network: (0 1)(2 3), then (0 2)(1 3), then (1 2).
    let s = sort_pairs(d.xz, c.xz, d.yw, c.yw);
    let t = sort_pairs(
        vec2<f32>(s.near_entry.x, s.far_entry.x),
        vec2<u32>(s.near_child.x, s.far_child.x),
        vec2<f32>(s.near_entry.y, s.far_entry.y),
        vec2<u32>(s.near_child.y, s.far_child.y),
    );
    let u = sort_pairs(t.near_entry.yy, t.near_child.yy, t.far_entry.xx, t.far_child.xx);
    return Children(
        vec4<f32>(t.near_entry.x, u.near_entry.x, u.far_entry.x, t.far_entry.y),
        vec4<u32>(t.near_child.x, u.near_child.x, u.far_child.x, t.far_child.y),
    );
}

// The traversal stack: pending children and their box entry distances. It lives at module
// scope because WGSL zero-initialises every variable: a function's array would be zeroed
// (2 × BVH_STACK_SIZE words of private memory) on every query, a module-scope one once per
// invocation. The two queries below never nest. The build refuses trees whose traversal
// could push more than BVH_STACK_SIZE children.
var<private> bvh_stack_ref: array<u32, BVH_STACK_SIZE>;
var<private> bvh_stack_t: array<f32, BVH_STACK_SIZE>;

// The nearest triangle hit of a ray: t, the triangle's position in `triangles` and its id.
struct TriangleHit {
    t: f32,
    index: u32,
    id: u32,
}

// The nearest hit on t in (T_MIN, t_max) among the triangles of the mesh whose nodes and
// triangles start at node_base and tri_base, the lowest id among hits at the same t;
// t = t_max when there is none (a hit exactly at t_max is not taken).
fn closest_triangle(ray: Ray, t_max: f32, node_base: u32, tri_base: u32) -> TriangleHit {
    // id 0 at t_max lets no triangle tie the caller's bound.
    var best = TriangleHit(t_max, 0u, 0u);
    let sh = make_shear(ray.dir);
    let br = make_box_ray(ray);
    var sp = 0u;
    var cur = 0u;
    loop {
        if (cur & BVH_LEAF) == 0u {
            let kids = ordered_children(bvh_nodes[node_base + cur], br, best.t);
            if kids.entry.x != BOX_MISS {
                // The nearest child next; the others (a prefix of the sorted lanes) wait on
                // the stack, the nearer on top.
                if kids.entry.y != BOX_MISS {
                    if kids.entry.z != BOX_MISS {
                        if kids.entry.w != BOX_MISS {
                            bvh_stack_ref[sp] = kids.child.w;
                            bvh_stack_t[sp] = kids.entry.w;
                            sp++;
                        }
                        bvh_stack_ref[sp] = kids.child.z;
                        bvh_stack_t[sp] = kids.entry.z;
                        sp++;
                    }
                    bvh_stack_ref[sp] = kids.child.y;
                    bvh_stack_t[sp] = kids.entry.y;
                    sp++;
                }
                cur = kids.child.x;
                continue;
            }
        } else {
            let range = leaf_range(cur);
            for (var k = tri_base + range.x; k < tri_base + range.y; k++) {
                let tri = triangles[k];
                let t = hit_triangle(tri, ray.origin, sh, NO_HIT);
                if t < best.t || (t == best.t && tri.id < best.id) {
                    best = TriangleHit(t, k, tri.id);
                }
            }
        }
        // Pop the next pending child that can still hold a closer hit.
        var found = false;
        while sp > 0u {
            sp--;
            if bvh_stack_t[sp] <= best.t {
                cur = bvh_stack_ref[sp];
                found = true;
                break;
            }
        }
        if !found {
            break;
        }
    }
    return best;
}

// Whether any triangle of the mesh at node_base and tri_base is hit on t in (T_MIN, t_max).
fn any_triangle(ray: Ray, t_max: f32, node_base: u32, tri_base: u32) -> bool {
    let sh = make_shear(ray.dir);
    let br = make_box_ray(ray);
    var sp = 0u;
    var cur = 0u;
    loop {
        if (cur & BVH_LEAF) == 0u {
            let kids = ordered_children(bvh_nodes[node_base + cur], br, t_max);
            if kids.entry.x != BOX_MISS {
                if kids.entry.y != BOX_MISS {
                    if kids.entry.z != BOX_MISS {
                        if kids.entry.w != BOX_MISS {
                            bvh_stack_ref[sp] = kids.child.w;
                            sp++;
                        }
                        bvh_stack_ref[sp] = kids.child.z;
                        sp++;
                    }
                    bvh_stack_ref[sp] = kids.child.y;
                    sp++;
                }
                cur = kids.child.x;
                continue;
            }
        } else {
            let range = leaf_range(cur);
            for (var k = tri_base + range.x; k < tri_base + range.y; k++) {
                if hit_triangle(triangles[k], ray.origin, sh, t_max) < t_max {
                    return true;
                }
            }
        }
        if sp == 0u {
            return false;
        }
        sp--;
        cur = bvh_stack_ref[sp];
    }
    return false;
}
