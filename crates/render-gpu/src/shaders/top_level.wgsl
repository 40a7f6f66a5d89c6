// The scene queries over the two-level BVH (steadyray_render::two_level): the frame's top
// level over its spheres, quads and mesh instances, each instance's mesh BVH (traversal.wgsl)
// with the ray in the instance's space, then the infinite planes. Written as the CPU
// reference writes them (crates/render-cpu/src/world.rs), so that both find the same hits:
// among leaves hit at the same t the lowest key wins, and a plane wins only when strictly
// nearer.

// The top level's own stack: an instance's mesh traversal runs inside it, on its own.
var<private> top_stack_ref: array<u32, BVH_STACK_SIZE>;
var<private> top_stack_t: array<f32, BVH_STACK_SIZE>;

// The smallest f32 above x, for x finite and positive: a bound below which hits at x count.
fn next_up(x: f32) -> f32 {
    return bitcast<f32>(bitcast<u32>(x) + 1u);
}

// The ray in `inst`'s mesh space, with the same t (its inv_len2 is not set: the triangle
// test does not read it).
fn ray_to_mesh(inst: Instance, ray: Ray) -> Ray {
    if inst.baked != 0u {
        return ray;
    }
    let o = ray.origin;
    let d = ray.dir;
    let x = inst.to_mesh_x;
    let y = inst.to_mesh_y;
    let z = inst.to_mesh_z;
    let origin = vec3<f32>(
        x.x * o.x + x.y * o.y + x.z * o.z + x.w,
        y.x * o.x + y.y * o.y + y.z * o.z + y.w,
        z.x * o.x + z.y * o.y + z.z * o.z + z.w,
    );
    let dir = vec3<f32>(
        x.x * d.x + x.y * d.y + x.z * d.z,
        y.x * d.x + y.y * d.y + y.z * d.z,
        z.x * d.x + z.y * d.y + z.z * d.z,
    );
    return Ray(origin, dir, 0.0);
}

// The world normal of a triangle of `inst` whose mesh normal is n.
fn normal_to_world(inst: Instance, n: vec3<f32>) -> vec3<f32> {
    if inst.baked != 0u {
        return n;
    }
    let m = vec3<f32>(
        inst.normal_x.x * n.x + inst.normal_x.y * n.y + inst.normal_x.z * n.z,
        inst.normal_y.x * n.x + inst.normal_y.y * n.y + inst.normal_y.z * n.z,
        inst.normal_z.x * n.x + inst.normal_z.y * n.y + inst.normal_z.z * n.z,
    );
    let inv = 1.0 / sqrt(m.x * m.x + m.y * m.y + m.z * m.z);
    return m * inv;
}

// The nearest hit of the leaf `leaf` that is no farther than best_t, as a Hit (t = NO_HIT
// when there is none).
fn hit_leaf(leaf: TopLeaf, ray: Ray, best_t: f32) -> Hit {
    if (leaf.index & TOP_INSTANCE) == 0u {
        return Hit(hit_shape(shapes[leaf.index], ray, NO_HIT), leaf.index, NO_INSTANCE);
    }
    let i = leaf.index & ~TOP_INSTANCE;
    let inst = instances[i];
    // Hits at best_t too, so that a lower key can take a tie.
    let bound = next_up(best_t);
    let tri = closest_triangle(ray_to_mesh(inst, ray), bound, inst.node_base, inst.tri_base);
    return Hit(select(NO_HIT, tri.t, tri.t < bound), tri.index, i);
}

// Whether a ray can be traversed: one whose origin or direction is not finite (a reflection
// off a NaN normal) meets nothing, as on the CPU (steadyray_accel's top level): its box tests
// could enter every box and run the stack past its end.
fn finite_ray(ray: Ray) -> bool {
    let largest = vec3<f32>(3.40282347e38);
    return all(abs(ray.origin) <= largest) && all(abs(ray.dir) <= largest);
}

fn closest_hit(ray: Ray) -> Hit {
    var best = Hit(NO_HIT, 0u, NO_INSTANCE);
    var best_key = 0xffffffffu;
    if frame.leaf_count != 0u && finite_ray(ray) {
        let br = make_box_ray(ray);
        var sp = 0u;
        var cur = 0u;
        loop {
            if (cur & BVH_LEAF) == 0u {
                let kids = ordered_children(top_nodes[cur], br, best.t);
                if kids.entry.x != BOX_MISS {
                    // The nearest child next; the others wait on the stack, nearer on top.
                    if kids.entry.y != BOX_MISS {
                        if kids.entry.z != BOX_MISS {
                            if kids.entry.w != BOX_MISS {
                                top_stack_ref[sp] = kids.child.w;
                                top_stack_t[sp] = kids.entry.w;
                                sp++;
                            }
                            top_stack_ref[sp] = kids.child.z;
                            top_stack_t[sp] = kids.entry.z;
                            sp++;
                        }
                        top_stack_ref[sp] = kids.child.y;
                        top_stack_t[sp] = kids.entry.y;
                        sp++;
                    }
                    cur = kids.child.x;
                    continue;
                }
            } else {
                let range = leaf_range(cur);
                for (var k = range.x; k < range.y; k++) {
                    let leaf = top_leaves[k];
                    let hit = hit_leaf(leaf, ray, best.t);
                    let tie = hit.t == best.t && hit.t < NO_HIT && leaf.key < best_key;
                    if hit.t < best.t || tie {
                        best = hit;
                        best_key = leaf.key;
                    }
                }
            }
            // Pop the next pending child that can still hold a hit no farther than best.
            var found = false;
            while sp > 0u {
                sp--;
                if top_stack_t[sp] <= best.t {
                    cur = top_stack_ref[sp];
                    found = true;
                    break;
                }
            }
            if !found {
                break;
            }
        }
    }
    for (var i = 0u; i < frame.plane_count; i++) {
        let t = hit_shape(shapes[i], ray, best.t);
        if t < best.t {
            best = Hit(t, i, NO_INSTANCE);
        }
    }
    return best;
}

// Whether leaf `leaf` is hit on t in (T_MIN, t_max).
fn leaf_blocks(leaf: TopLeaf, ray: Ray, t_max: f32) -> bool {
    if (leaf.index & TOP_INSTANCE) == 0u {
        return hit_shape(shapes[leaf.index], ray, t_max) < t_max;
    }
    let inst = instances[leaf.index & ~TOP_INSTANCE];
    return any_triangle(ray_to_mesh(inst, ray), t_max, inst.node_base, inst.tri_base);
}

// Whether anything is hit on t in (T_MIN, t_max).
fn occluded(ray: Ray, t_max: f32) -> bool {
    for (var i = 0u; i < frame.plane_count; i++) {
        if hit_shape(shapes[i], ray, t_max) < t_max {
            return true;
        }
    }
    if frame.leaf_count == 0u || !finite_ray(ray) {
        return false;
    }
    let br = make_box_ray(ray);
    var sp = 0u;
    var cur = 0u;
    loop {
        if (cur & BVH_LEAF) == 0u {
            let kids = ordered_children(top_nodes[cur], br, t_max);
            if kids.entry.x != BOX_MISS {
                if kids.entry.y != BOX_MISS {
                    if kids.entry.z != BOX_MISS {
                        if kids.entry.w != BOX_MISS {
                            top_stack_ref[sp] = kids.child.w;
                            sp++;
                        }
                        top_stack_ref[sp] = kids.child.z;
                        sp++;
                    }
                    top_stack_ref[sp] = kids.child.y;
                    sp++;
                }
                cur = kids.child.x;
                continue;
            }
        } else {
            let range = leaf_range(cur);
            for (var k = range.x; k < range.y; k++) {
                if leaf_blocks(top_leaves[k], ray, t_max) {
                    return true;
                }
            }
        }
        if sp == 0u {
            return false;
        }
        sp--;
        cur = top_stack_ref[sp];
    }
    return false;
}
