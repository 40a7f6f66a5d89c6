// The Whitted integrator of docs/shading.md: one thread per pixel, a loop over the pixel's
// samples, each following a single chain of rays up to depth R. Rays are counted per
// workgroup and written out once per workgroup.

var<workgroup> group_rays: array<atomic<u32>, COUNTER_SLOTS>;
// Shadow rays traced by this thread (at most S·(R + 1)·lights: exact below 16,000 lights).
var<private> shadow_rays: u32;

// local(p, n, albedo): ambient plus the unoccluded point lights, no 1/π.
fn local_shading(p: vec3<f32>, n: vec3<f32>, albedo: vec3<f32>) -> vec3<f32> {
    var irradiance = vec3<f32>(frame.ambient);
    let origin = p + n * EPS;
    for (var i = 0u; i < frame.light_count; i++) {
        let light = lights[i];
        let to_light = light.position - p;
        let dist2 = dot(to_light, to_light);
        let dist = sqrt(dist2);
        let l = to_light / dist;
        let cos_l = dot(n, l);
        if cos_l > 0.0 {
            shadow_rays += 1u;
            if !occluded(make_ray(origin, l), dist - T_MIN) {
                irradiance += light.intensity * cos_l / dist2;
            }
        }
    }
    return albedo * irradiance;
}

// The mirror direction d - 2·dot(d, n)·n.
fn mirror(d: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    return d - 2.0 * dot(d, n) * n;
}

// The radiance of sample `sample` of pixel (px, py), whose eye ray leaves `eye` along `dir`.
fn trace_sample(px: u32, py: u32, sample: u32, eye: vec3<f32>, dir: vec3<f32>) -> vec3<f32> {
    var ray = make_ray(eye, dir);
    var w = vec3<f32>(1.0);
    var radiance = vec3<f32>(0.0);
    for (var k = 0u; k <= frame.max_depth; k++) {
        atomicAdd(&group_rays[k], 1u);
        let hit = closest_hit(ray);
        if hit.t >= NO_HIT {
            record_miss();
            radiance += w * frame.background;
            break;
        }
        let d = ray.dir;
        let p = ray.origin + hit.t * d;
        let surface = surface_at(hit, p);
        let entering = dot(surface.normal, d) < 0.0;
        let n = select(-surface.normal, surface.normal, entering);
        let m = materials[surface.material];
        let goes_on = k < frame.max_depth;
        record_hit(hit, n, goes_on && m.kind == MAT_MIRROR, goes_on && m.kind == MAT_DIELECTRIC);
        if m.kind == MAT_EMISSIVE {
            radiance += w * m.colour;
            break;
        }
        if m.kind == MAT_DIFFUSE {
            radiance += w * local_shading(p, n, diffuse_albedo(m, hit, p));
            break;
        }
        if k == frame.max_depth {
            // A mirror or dielectric here: a deeper limit would trace one more ray.
            atomicAdd(&group_rays[frame.max_depth + 3u], 1u);
            radiance += w * local_shading(p, n, m.colour);
            break;
        }
        if m.kind == MAT_MIRROR {
            w *= m.colour;
            ray = make_ray(p + n * EPS, mirror(d, n));
            continue;
        }
        // Dielectric: Fresnel-weighted choice between reflection and refraction.
        let eta = select(m.ior, 1.0 / m.ior, entering);
        let cos_i = -dot(d, n);
        let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
        var refracts = false;
        var cos_t = 0.0;
        if sin2_t <= 1.0 {
            cos_t = sqrt(1.0 - sin2_t);
            let r_s = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
            let r_p = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
            let fresnel = (r_s * r_s + r_p * r_p) * 0.5;
            refracts = branch_random(px, py, sample, k) >= fresnel;
        }
        if refracts {
            w *= m.colour;
            ray = make_ray(p - n * EPS, eta * d + (eta * cos_i - cos_t) * n);
        } else {
            ray = make_ray(p + n * EPS, mirror(d, n));
        }
    }
    return radiance;
}

// The eye ray direction through pixel (px, py) at sub-pixel offset uv in this frame.
fn eye_ray_dir(px: u32, py: u32, uv: vec2<f32>) -> vec3<f32> {
    return pixel_ray_dir(
        frame.forward,
        frame.right,
        frame.true_up,
        vec2<f32>(frame.half_width, frame.half_height),
        vec2<u32>(frame.width, frame.height),
        px,
        py,
        uv,
    );
}

// Traces the samples of pixel (px, py) in this dispatch's range. The pixel's running sum
// waits in the image between dispatches (alpha 0), and the dispatch of its last sample
// writes the mean: the same additions in the same order as in one dispatch.
fn render_pixel(px: u32, py: u32) {
    shadow_rays = 0u;
    let n = samples_for_pixel(px, py, frame.spp);
    let first = sample_range.first;
    if first >= n {
        return;
    }
    let end = min(sample_range.end, n);
    let index = py * frame.width + px;
    var sum = vec3<f32>(0.0);
    if first > 0u {
        sum = image[index].xyz;
    }
    for (var i = first; i < end; i++) {
        let dir = eye_ray_dir(px, py, jittered_sample(i, n, frame.jitter, frame.still_frame));
        record_begin(frame.temporal != 0u && i == 0u, frame.eye, dir);
        sum += trace_sample(px, py, i + frame.sample_base, frame.eye, dir);
    }
    if end == n {
        image[index] = vec4<f32>(sum / f32(n), 1.0);
    } else {
        image[index] = vec4<f32>(sum, 0.0);
    }
    if frame.temporal != 0u && first == 0u {
        record_store(index);
    }
    let before = atomicAdd(&group_rays[frame.max_depth + 1u], shadow_rays);
    if before > 0xffffffffu - shadow_rays {
        atomicAdd(&group_rays[frame.max_depth + 2u], 1u);
    }
}

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn render(
    @builtin(global_invocation_id) gid: vec3<u32>,
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    for (var i = lid; i < COUNTER_SLOTS; i += WORKGROUP_SIZE * WORKGROUP_SIZE) {
        atomicStore(&group_rays[i], 0u);
    }
    workgroupBarrier();
    if gid.x < frame.width && gid.y < frame.height {
        render_pixel(gid.x, gid.y);
    }
    workgroupBarrier();
    let base = (wid.y * frame.groups_x + wid.x) * frame.counter_stride;
    if sample_range.first == 0u {
        for (var i = lid; i < frame.counter_stride; i += WORKGROUP_SIZE * WORKGROUP_SIZE) {
            group_counts[base + i] = atomicLoad(&group_rays[i]);
        }
    } else if lid == 0u {
        // A later dispatch adds its counts to the frame's, carrying out of the shadow count.
        let shadow = base + frame.max_depth + 1u;
        let shadow_before = group_counts[shadow];
        for (var i = 0u; i < frame.counter_stride; i++) {
            group_counts[base + i] += atomicLoad(&group_rays[i]);
        }
        if group_counts[shadow] < shadow_before {
            group_counts[shadow + 1u] += 1u;
        }
    }
}
