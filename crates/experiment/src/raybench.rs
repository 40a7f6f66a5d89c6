//! `steadyray raybench`: ray-casting throughput of the triangle BVH alone, without shading.
//!
//! One primary ray through each pixel centre (the pixel convention of `docs/corridor.md`),
//! then one cosine-weighted diffuse bounce ray from each primary hit (seeded, so every run
//! traces the same rays). Both sets are traced `--reps` times for their closest hit; the
//! command prints one JSON line with the triangle count, load and build times, the median
//! rays per second of each set (the BVH build excluded), the hit fractions, the thread
//! count and the traversal's SIMD form (CPU) or the device (GPU), how the time was taken
//! and the camera.
//!
//! `--dump-rays FILE` also writes the triangles and both ray sets, with their t ranges and
//! the hits found, for tracing the same rays elsewhere (`scripts/embree/` traces them with
//! Embree; the format is in [`crate::ray_dump`]).
//!
//! On the GPU (`--backend gpu`, [`GpuRayCaster`]) the mesh is uploaded once, primary rays
//! are generated in the kernel, bounce rays are made on the host from the primary hits and
//! uploaded, and each repetition is one dispatch timed by GPU timestamps (the kernel alone:
//! no upload or readback), after an untimed warm-up.

use crate::backend::requested_gpu_options;
use crate::ray_dump::{self, DumpRay, RaySet};
use anyhow::{Context, bail};
use glam::{Vec3, Vec3A};
use serde::{Deserialize, Serialize};
use std::path::PathBuf;
use std::time::Instant;
use steadyray_accel::Bvh;
use steadyray_render::TimingSource;
use steadyray_render::sampling::{cosine_direction, pcg_hash, unit_from_hash};
use steadyray_render_cpu::raycast::{Cast, T_MAX, cast_all};
use steadyray_render_gpu::layout::GpuCastRay;
use steadyray_render_gpu::{CastOutcome, GpuOptions, GpuRayCaster, list_adapters};
use steadyray_scene::Camera;
use steadyray_scene::Transform;
use steadyray_scene::mesh_import::import_mesh;

/// Where `raybench` traces its rays.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RaybenchBackend {
    /// A hardware GPU adapter where there is one (narrowed by `STEADYRAY_ADAPTER`), else the
    /// CPU, as every rendering command's `--backend auto`.
    Auto,
    /// The 8-wide BVH on the CPU, rayon tasks over chunks of rays.
    Cpu,
    /// The 4-wide BVH in WGSL on a GPU adapter (software ones such as lavapipe included;
    /// `STEADYRAY_ADAPTER=name` picks one by name).
    Gpu,
}

/// The tracer `backend` asks for, saying on stderr which one it picked; `auto` falls back
/// to the CPU where no hardware adapter is present or it fails to start.
fn open_tracer(
    backend: RaybenchBackend,
    corners: &[[Vec3; 3]],
    bvh: &Bvh,
) -> anyhow::Result<Tracer> {
    let options = match backend {
        RaybenchBackend::Cpu => return Ok(Tracer::Cpu),
        RaybenchBackend::Gpu => requested_gpu_options(),
        RaybenchBackend::Auto => {
            let wanted = requested_gpu_options()
                .adapter_name
                .map(|n| n.to_lowercase());
            let hardware = list_adapters().into_iter().find(|a| {
                !a.is_software
                    && wanted
                        .as_deref()
                        .is_none_or(|want| a.name.to_lowercase().contains(want))
            });
            let Some(adapter) = hardware else {
                eprintln!("steadyray: raybench on the CPU (auto: no hardware GPU adapter)");
                return Ok(Tracer::Cpu);
            };
            GpuOptions {
                adapter_name: Some(adapter.name),
                allow_software: false,
            }
        }
    };
    match GpuRayCaster::new(&options, corners, bvh) {
        Ok(caster) => {
            eprintln!("steadyray: raybench on {}", caster.device_description());
            Ok(Tracer::Gpu(Box::new(caster)))
        }
        Err(e) if backend == RaybenchBackend::Auto => {
            eprintln!("steadyray: raybench on the CPU (auto: the GPU failed to start: {e})");
            Ok(Tracer::Cpu)
        }
        Err(e) => Err(anyhow::Error::new(e).context("the gpu backend is not available")),
    }
}

/// What `raybench` measures: a mesh, a view and where to trace its rays.
#[derive(Clone, Debug)]
pub struct RaybenchConfig {
    /// The mesh file (.obj).
    pub mesh: PathBuf,
    /// `auto` (the mesh's bounding box, seen from +z) or JSON
    /// `{"eye":[x,y,z],"target":[x,y,z],"up":[x,y,z],"vfov":degrees}`.
    pub camera: String,
    /// Image width in pixels (one primary ray per pixel).
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Where to trace.
    pub backend: RaybenchBackend,
    /// Timed repetitions of each ray set; the median is reported.
    pub reps: u32,
    /// Worker threads on the CPU, for the BVH build and CPU tracing (0: one per available
    /// CPU), each taking the next chunk of 1024 rays until none is left.
    pub threads: usize,
    /// Seed of the bounce directions.
    pub seed: u32,
    /// Split every triangle into four at its edge midpoints this many times before building:
    /// the same surface from 4^N times the triangles, for measuring how cost grows with
    /// triangle count at a fixed view (at most 6).
    pub subdivide: u32,
    /// Also write the triangles and the exact rays traced (both sets, with their t ranges
    /// and closest hits) to this file, in the binary format `scripts/embree/` reads.
    pub dump_rays: Option<PathBuf>,
}

/// `tris` with each triangle split into four at its edge midpoints, `times` times over.
fn subdivide(mut tris: Vec<[Vec3; 3]>, times: u32) -> Vec<[Vec3; 3]> {
    for _ in 0..times {
        tris = tris
            .iter()
            .flat_map(|&[a, b, c]| {
                let (ab, bc, ca) = ((a + b) * 0.5, (b + c) * 0.5, (c + a) * 0.5);
                [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]
            })
            .collect();
    }
    tris
}

/// The camera as `--camera` takes it and the report prints it.
#[derive(Clone, Copy, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct CameraSpec {
    eye: [f32; 3],
    target: [f32; 3],
    up: [f32; 3],
    vfov: f32,
}

impl CameraSpec {
    /// The `--camera` value: `auto` frames the whole mesh (bounding sphere of its box) at
    /// a 45° field of view, looking along -z.
    fn parse(text: &str, positions: &[Vec3]) -> anyhow::Result<Self> {
        if text == "auto" {
            let (lo, hi) = positions
                .iter()
                .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &p| {
                    (lo.min(p), hi.max(p))
                });
            let center = (lo + hi) * 0.5;
            let radius = ((hi - lo).length() * 0.5).max(f32::MIN_POSITIVE);
            let vfov = 45.0f32;
            let distance = radius / (vfov.to_radians() * 0.5).sin();
            return Ok(Self {
                eye: (center + Vec3::Z * distance).to_array(),
                target: center.to_array(),
                up: [0.0, 1.0, 0.0],
                vfov,
            });
        }
        let spec: Self =
            serde_json::from_str(text).context("--camera: not `auto` or valid JSON")?;
        let eye = Vec3::from(spec.eye);
        let (target, up) = (Vec3::from(spec.target), Vec3::from(spec.up));
        if !(eye.is_finite() && target.is_finite() && up.is_finite()) || eye == target {
            bail!("--camera: eye, target and up must be finite and eye must differ from target");
        }
        if up.length_squared() == 0.0 || !(spec.vfov > 0.0 && spec.vfov < 180.0) {
            bail!("--camera: up must not be zero and vfov must be in (0, 180) degrees");
        }
        Ok(spec)
    }

    fn camera(&self) -> Camera {
        Camera::look_at(
            self.eye.into(),
            self.target.into(),
            self.up.into(),
            self.vfov,
        )
    }
}

/// The report line.
#[derive(Debug, Serialize)]
struct Report {
    mesh: String,
    backend: &'static str,
    triangles: usize,
    subdivide: u32,
    degenerate_dropped: usize,
    load_s: f64,
    build_s: f64,
    width: u32,
    height: u32,
    reps: u32,
    /// Worker threads (CPU backend only).
    #[serde(skip_serializing_if = "Option::is_none")]
    threads: Option<usize>,
    /// The compiled form of the CPU traversal that ran: avx512, avx2 or portable (CPU
    /// backend only).
    #[serde(skip_serializing_if = "Option::is_none")]
    simd: Option<&'static str>,
    /// The GPU adapter and driver (GPU backend only).
    #[serde(skip_serializing_if = "Option::is_none")]
    device: Option<String>,
    /// How the rays/s were timed: "timestamps" (GPU timestamp queries around each
    /// dispatch) or "wall" (the host clock around each repetition).
    timing: &'static str,
    primary_rays: usize,
    primary_rays_per_s: f64,
    primary_hit_fraction: f64,
    bounce_rays: usize,
    bounce_rays_per_s: f64,
    bounce_hit_fraction: f64,
    primary_rays_per_s_reps: Vec<f64>,
    bounce_rays_per_s_reps: Vec<f64>,
    camera: CameraSpec,
}

fn median(values: &[f64]) -> f64 {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    match v.len() {
        0 => 0.0,
        n if n % 2 == 1 => v[n / 2],
        n => 0.5 * (v[n / 2 - 1] + v[n / 2]),
    }
}

/// Where the rays are traced: the CPU's worker threads, or a GPU holding the mesh.
enum Tracer {
    Cpu,
    Gpu(Box<GpuRayCaster>),
}

/// Rays per second of each timed repetition of `outcome` over `rays` rays.
fn gpu_rates(outcome: &CastOutcome, rays: usize) -> Vec<f64> {
    outcome
        .times_ms
        .iter()
        .map(|&ms| rays as f64 / (ms * 1e-3))
        .collect()
}

/// Stores the GPU's hits in `casts`, in order.
fn take_hits(casts: &mut [Cast], outcome: &CastOutcome) {
    for (cast, &hit) in casts.iter_mut().zip(&outcome.hits) {
        cast.hit = hit;
    }
}

/// One cosine-weighted bounce ray from each hit of `primary` (seeded by the ray's index and
/// `seed`), leaving the surface on the side the primary ray came from.
fn bounce_casts(primary: &[Cast], corners: &[[Vec3; 3]], seed: u32) -> Vec<Cast> {
    primary
        .iter()
        .enumerate()
        .filter_map(|(i, c)| {
            let (t, tri) = c.hit?;
            let [a, b, cc] = corners[tri as usize].map(Vec3A::from);
            let mut n = (b - a).cross(cc - a).normalize();
            if n.dot(c.dir) > 0.0 {
                n = -n;
            }
            let hash = pcg_hash(pcg_hash(i as u32) ^ seed);
            let (u1, u2) = (unit_from_hash(hash), unit_from_hash(pcg_hash(hash)));
            Some(Cast {
                origin: c.origin + t * c.dir + n * steadyray_accel::T_MIN,
                dir: cosine_direction(n, u1, u2),
                hit: None,
            })
        })
        .collect()
}

/// Measures the ray-casting throughput `args` asks for and prints it as one JSON line.
pub fn run(args: &RaybenchConfig) -> anyhow::Result<()> {
    if args.width == 0 || args.height == 0 || args.reps == 0 {
        bail!("--width, --height and --reps must be at least 1");
    }
    let start = Instant::now();
    let imported = import_mesh(&args.mesh, &Transform::default())?;
    let load_s = start.elapsed().as_secs_f64();
    let mesh = imported.mesh;
    let corners = subdivide(
        (0..mesh.triangles.len())
            .map(|i| mesh.triangle(i))
            .collect(),
        args.subdivide,
    );
    let spec = CameraSpec::parse(&args.camera, &mesh.positions)?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads)
        .build()
        .context("cannot start the worker threads")?;
    let start = Instant::now();
    let bvh = pool
        .install(|| Bvh::build(&corners))
        .with_context(|| format!("mesh file {}", args.mesh.display()))?;
    let build_s = start.elapsed().as_secs_f64();
    let mut tracer = open_tracer(args.backend, &corners, &bvh)?;

    let (w, h) = (args.width, args.height);
    let frame = spec.camera().frame(w, h);
    let eye = Vec3A::from(frame.eye);
    // The GPU generates these directions itself (the same arithmetic); the host's copies
    // place the bounce rays.
    let mut primary: Vec<Cast> = (0..h)
        .flat_map(|py| (0..w).map(move |px| (px, py)))
        .map(|(px, py)| Cast {
            origin: eye,
            dir: frame.ray_dir(px, py, 0.5, 0.5, w, h).into(),
            hit: None,
        })
        .collect();
    let mut timings = Vec::new();
    let primary_rates = match &mut tracer {
        Tracer::Cpu => cast_all(&pool, &bvh, &mut primary, args.reps),
        Tracer::Gpu(caster) => {
            let outcome = caster.cast_primary(&frame, w, h, args.reps)?;
            take_hits(&mut primary, &outcome);
            timings.push(outcome.timing);
            gpu_rates(&outcome, primary.len())
        }
    };

    let mut bounce = bounce_casts(&primary, &corners, args.seed);
    let bounce_rates = match &mut tracer {
        Tracer::Cpu => cast_all(&pool, &bvh, &mut bounce, args.reps),
        Tracer::Gpu(caster) => {
            let rays: Vec<GpuCastRay> = bounce
                .iter()
                .map(|c| GpuCastRay::new(c.origin.into(), c.dir.into()))
                .collect();
            let outcome = caster.cast_rays(&rays, args.reps)?;
            take_hits(&mut bounce, &outcome);
            timings.push(outcome.timing);
            gpu_rates(&outcome, bounce.len())
        }
    };

    let hit_fraction = |casts: &[Cast]| {
        casts.iter().filter(|c| c.hit.is_some()).count() as f64 / casts.len().max(1) as f64
    };
    let timestamps =
        !timings.is_empty() && timings.iter().all(|&t| t == TimingSource::GpuTimestamps);
    let (backend, threads, simd, device) = match &tracer {
        Tracer::Cpu => (
            "cpu",
            Some(pool.current_num_threads()),
            Some(steadyray_accel::cpu_traversal_simd()),
            None,
        ),
        Tracer::Gpu(caster) => ("gpu", None, None, Some(caster.device_description())),
    };
    let report = Report {
        mesh: args.mesh.display().to_string(),
        backend,
        triangles: bvh.triangle_count(),
        subdivide: args.subdivide,
        degenerate_dropped: imported.degenerate_dropped,
        load_s,
        build_s,
        width: w,
        height: h,
        reps: args.reps,
        threads,
        simd,
        device,
        timing: if timestamps { "timestamps" } else { "wall" },
        primary_rays: primary.len(),
        primary_rays_per_s: median(&primary_rates),
        primary_hit_fraction: hit_fraction(&primary),
        bounce_rays: bounce.len(),
        bounce_rays_per_s: median(&bounce_rates),
        bounce_hit_fraction: hit_fraction(&bounce),
        primary_rays_per_s_reps: primary_rates,
        bounce_rays_per_s_reps: bounce_rates,
        camera: spec,
    };
    if let Some(path) = &args.dump_rays {
        let records = |casts: &[Cast]| -> Vec<DumpRay> {
            casts
                .iter()
                .map(|c| DumpRay::new(c.origin, c.dir, (steadyray_accel::T_MIN, T_MAX), c.hit))
                .collect()
        };
        let (primary, bounce) = (records(&primary), records(&bounce));
        let sets = [
            RaySet {
                name: "primary",
                rays: &primary,
            },
            RaySet {
                name: "bounce",
                rays: &bounce,
            },
        ];
        ray_dump::write(path, &corners, &sets)?;
    }
    println!("{}", serde_json::to_string(&report)?);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each split keeps the surface: four times the triangles, the same total area and the
    /// same corners' bounding box.
    #[test]
    fn subdividing_keeps_the_surface() {
        let tris = vec![
            [Vec3::ZERO, Vec3::X, Vec3::Y],
            [Vec3::new(1.0, 2.0, 3.0), Vec3::new(-2.0, 0.5, 1.0), Vec3::Z],
        ];
        let area = |t: &[[Vec3; 3]]| -> f32 {
            t.iter()
                .map(|[a, b, c]| 0.5 * (*b - *a).cross(*c - *a).length())
                .sum()
        };
        for times in 0..=3 {
            let split = subdivide(tris.clone(), times);
            assert_eq!(split.len(), tris.len() * 4usize.pow(times));
            assert!((area(&split) - area(&tris)).abs() < 1e-4 * area(&tris));
        }
    }
}
