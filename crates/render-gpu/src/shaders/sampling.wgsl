// Mirrors steadyray_render::sampling bit for bit (integer hashing, exact float steps).

fn pcg_hash(x: u32) -> u32 {
    let state = x * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

fn unit_from_hash(h: u32) -> f32 {
    return f32(h >> 8u) * (1.0 / 16777216.0);
}

fn branch_random(px: u32, py: u32, sample: u32, depth: u32) -> f32 {
    var h = pcg_hash(px);
    h = pcg_hash(h ^ py);
    h = pcg_hash(h ^ sample);
    h = pcg_hash(h ^ depth);
    return unit_from_hash(h);
}

const R2_A: f32 = 0.7548777;
const R2_B: f32 = 0.5698403;

fn sample_offset(i: u32, n: u32) -> vec2<f32> {
    let odd = n & 1u;
    if i < odd || n <= 1u {
        return vec2<f32>(0.5, 0.5);
    }
    let j = i - odd;
    let k = f32(j / 2u + 1u);
    let p = vec2<f32>(0.5 + k * R2_A, 0.5 + k * R2_B);
    let q = p - floor(p);
    if (j & 1u) == 0u {
        return q;
    }
    let m = vec2<f32>(1.0, 1.0) - q;
    return m - floor(m);
}

// The temporal mode's sub-pixel position of a sample at `offset` in a frame of jitter j:
// frac(offset + j), written as t - floor(t) (steadyray_render::temporal::jittered).
fn jittered(offset: vec2<f32>, j: vec2<f32>) -> vec2<f32> {
    let t = offset + j;
    return t - floor(t);
}

// Sample i of n in a frame of jitter j, still_frame its index in a still view (else 0). A
// moving frame: each mirrored pair moved by +j and -j, so that a pixel of two or more samples
// keeps its centroid at the centre; the centre sample of an odd n >= 3 stays put. A still
// frame: still_sample (steadyray_render::temporal::jittered_sample).
fn jittered_sample(i: u32, n: u32, j: vec2<f32>, still_frame: u32) -> vec2<f32> {
    if still_frame != 0u {
        return still_sample(i, n, j, still_frame);
    }
    let offset = sample_offset(i, n);
    let odd = n & 1u;
    if n <= 1u {
        return jittered(offset, j);
    }
    if i < odd {
        return offset;
    }
    if ((i - odd) & 1u) == 1u {
        return jittered(offset, -j);
    }
    return jittered(offset, j);
}

// The R2 sequence's generators 1/phi2, 1/phi2^2 in 0.32 fixed point (the jitter's).
const R2_STEP: vec2<u32> = vec2<u32>(0xc13fa9a9u, 0x91e10da6u);

// Sample i of n in frame still_frame >= 1 of a still view: the frame's own mirrored R2 pairs
// (those after the still_frame * floor(n / 2) of the frames before it), in 0.32 fixed point;
// the one sample of n = 1 at 0.5 + j, the centre sample of an odd n >= 3 at j
// (steadyray_render::temporal::still_sample).
fn still_sample(i: u32, n: u32, j: vec2<f32>, still_frame: u32) -> vec2<f32> {
    let odd = n & 1u;
    if n <= 1u {
        return jittered(vec2<f32>(0.5, 0.5), j);
    }
    if i < odd {
        return j;
    }
    let pair = i - odd;
    let m = pair / 2u + 1u + still_frame * (n / 2u);
    var point = vec2<u32>(m) * R2_STEP + vec2<u32>(0x80000000u);
    if (pair & 1u) == 1u {
        point = vec2<u32>(0u) - point;
    }
    return vec2<f32>(point >> vec2<u32>(8u)) * (1.0 / 16777216.0);
}

var<private> BAYER8: array<u32, 64> = array<u32, 64>(
    0u, 32u, 8u, 40u, 2u, 34u, 10u, 42u,
    48u, 16u, 56u, 24u, 50u, 18u, 58u, 26u,
    12u, 44u, 4u, 36u, 14u, 46u, 6u, 38u,
    60u, 28u, 52u, 20u, 62u, 30u, 54u, 22u,
    3u, 35u, 11u, 43u, 1u, 33u, 9u, 41u,
    51u, 19u, 59u, 27u, 49u, 17u, 57u, 25u,
    15u, 47u, 7u, 39u, 13u, 45u, 5u, 37u,
    63u, 31u, 55u, 23u, 61u, 29u, 53u, 21u,
);

fn samples_for_pixel(px: u32, py: u32, spp: f32) -> u32 {
    let whole = floor(spp);
    let frac = spp - whole;
    let threshold = (f32(BAYER8[(py & 7u) * 8u + (px & 7u)]) + 0.5) / 64.0;
    return u32(whole) + select(0u, 1u, frac > threshold);
}
