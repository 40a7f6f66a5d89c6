// Sums the per-workgroup ray counters into 64-bit totals: one workgroup per counter.

var<workgroup> partial: array<vec2<u32>, REDUCE_SIZE>;

// 64-bit addition of (low, high) pairs.
fn add64(a: vec2<u32>, b: vec2<u32>) -> vec2<u32> {
    let low = a.x + b.x;
    return vec2<u32>(low, a.y + b.y + select(0u, 1u, low < a.x));
}

@compute @workgroup_size(REDUCE_SIZE, 1, 1)
fn reduce_counts(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let counter = wid.x;
    var sum = vec2<u32>(0u);
    for (var g = lid; g < frame.group_count; g += REDUCE_SIZE) {
        sum = add64(sum, vec2<u32>(group_counts[g * frame.counter_stride + counter], 0u));
    }
    partial[lid] = sum;
    workgroupBarrier();
    for (var half = REDUCE_SIZE / 2u; half > 0u; half /= 2u) {
        if lid < half {
            partial[lid] = add64(partial[lid], partial[lid + half]);
        }
        workgroupBarrier();
    }
    if lid == 0u {
        totals[counter] = partial[0];
    }
}
