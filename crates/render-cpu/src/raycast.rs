//! Casting rays through a triangle BVH on the CPU's worker threads, and timing it: the CPU
//! side of `steadyray raybench`, beside the GPU's `steadyray_render_gpu::GpuRayCaster`.

use glam::Vec3A;
use rayon::prelude::*;
use std::time::Instant;
use steadyray_accel::Bvh;

/// The end of every ray's t range: rays hit on (`T_MIN`, [`T_MAX`]).
pub const T_MAX: f32 = f32::INFINITY;

/// Rays per task of the CPU's worker threads.
const CHUNK: usize = 1024;

/// A ray and, after tracing, its closest hit (t, input triangle index).
#[derive(Clone, Copy, Debug)]
pub struct Cast {
    /// Where the ray starts.
    pub origin: Vec3A,
    /// Its direction.
    pub dir: Vec3A,
    /// Its closest hit once traced.
    pub hit: Option<(f32, u32)>,
}

/// Traces every cast `reps` times on `pool`'s threads, leaving each its closest hit;
/// returns rays per second of each repetition.
///
/// Every chunk of `CHUNK` rays is a task of its own (`with_max_len(1)`). Left to itself,
/// rayon cut the bounce rays into a few long runs of chunks that cannot be split once
/// started, and on two threads one thread then finished its last run alone: 8.6 % fewer
/// bounce rays per second (bunny, same process, alternating; primary rays and one thread
/// unchanged).
pub fn cast_all(pool: &rayon::ThreadPool, bvh: &Bvh, casts: &mut [Cast], reps: u32) -> Vec<f64> {
    (0..reps)
        .map(|_| {
            let start = Instant::now();
            pool.install(|| {
                casts
                    .par_chunks_mut(CHUNK)
                    .with_max_len(1)
                    .for_each(|chunk| {
                        for c in chunk {
                            c.hit = bvh.closest(c.origin, c.dir, T_MAX);
                        }
                    })
            });
            casts.len() as f64 / start.elapsed().as_secs_f64()
        })
        .collect()
}
