//! The reference Whitted ray tracer of steadyray, on the CPU with rayon.
//!
//! It computes exactly the shading model of `docs/shading.md` in `f32`; the GPU backend is
//! checked against it. Spheres, two-sided quads and mesh copies sit in a two-level BVH
//! (`steadyray_render::two_level`): a top level over the frame's objects, updated when the
//! scene time changes, and one bottom-level triangle BVH per mesh (watertight triangle test),
//! shared by its copies. Infinite planes are tested one by one.

mod device;
mod integrator;
mod material;
pub mod optics;
mod plane;
mod probe;
mod quad;
mod ray;
pub mod raycast;
mod render;
mod simd;
mod sphere;
mod temporal;
mod triangle;
mod world;

pub use probe::{PathTrace, TracedRay};
pub use ray::{EPS, T_MIN};

use glam::{Vec3, Vec3A};
use integrator::{SampleId, trace};
use rayon::prelude::*;
use render::{FrameOutputs, SamplePattern};
use std::time::Instant;
use steadyray_render::temporal::sample_base;
use steadyray_render::tonemap::linear_to_srgb8_fast;
use steadyray_render::{
    BackendInfo, FrameBudget, FrameStats, Image, MAX_DEPTH, Picture, Presented, RenderError,
    RenderSettings, Renderer, SampleStream, SettingsError, TemporalSettings, TimingSource,
    check_camera, check_time,
};
use steadyray_scene::{Camera, Scene};
use temporal::History;
use world::World;

/// The CPU renderer: a prepared scene, its own rayon thread pool, the image of the last
/// frame (reused across frames of the same size), the samples plain frames draw and, in the
/// temporal mode, the history and the camera of the warp on display, if any.
pub struct CpuRenderer {
    pool: rayon::ThreadPool,
    world: Option<World>,
    image: Option<Image>,
    stream: SampleStream,
    history: Option<History>,
    /// The camera of the last warped refresh while it is on display: its picture is made
    /// again when read, rather than copied on every warp.
    warped: Option<Camera>,
    /// The time budget plain frames are rendered within, if any.
    budget: Option<FrameBudget>,
}

impl Default for CpuRenderer {
    fn default() -> Self {
        Self::new()
    }
}

impl CpuRenderer {
    /// A renderer using one thread per available CPU.
    ///
    /// # Panics
    /// If the operating system cannot start the worker threads.
    pub fn new() -> Self {
        Self::with_threads(0)
    }

    /// A renderer using `threads` worker threads (0: one per available CPU).
    ///
    /// # Panics
    /// If the operating system cannot start the worker threads.
    pub fn with_threads(threads: usize) -> Self {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .thread_name(|i| format!("steadyray-cpu-{i}"))
            .build()
            .expect("cannot start the CPU renderer's worker threads");
        Self {
            pool,
            world: None,
            image: None,
            stream: SampleStream::Frames,
            history: None,
            warped: None,
            budget: None,
        }
    }

    /// The number of worker threads.
    pub fn threads(&self) -> usize {
        self.pool.current_num_threads()
    }

    /// Traces one ray from `origin` along `dir` exactly as the eye sample `sample` of pixel
    /// `pixel` would be traced with depth `max_depth` (the pixel and sample only choose the
    /// dielectric branches), and returns its whole path. Moving objects are where the last
    /// rendered frame had them (at time 0 after `load_scene`).
    pub fn trace_ray(
        &self,
        origin: Vec3,
        dir: Vec3,
        pixel: (u32, u32),
        sample: u32,
        max_depth: u32,
    ) -> Result<PathTrace, RenderError> {
        if max_depth > MAX_DEPTH {
            return Err(SettingsError::BadDepth(max_depth).into());
        }
        let world = self.world.as_ref().ok_or(RenderError::NoScene)?;
        let mut path = PathTrace::default();
        let id = SampleId {
            px: pixel.0,
            py: pixel.1,
            sample,
        };
        let ray = ray::Ray::new(origin.into(), Vec3A::from(dir));
        path.radiance = trace(world, ray, id, max_depth, &mut path).into();
        Ok(path)
    }

    /// Where rays from `origin` along each of `dirs` first meet a surface of the world at
    /// scene time `time_s`: per ray, t of the nearest hit at `origin + t · dir` and the index
    /// (in the scene's objects) of the object hit, or `None` when it leaves the scene. The
    /// primary hits an eye ray would shade: what measuring motion on screen reprojects.
    pub fn first_hits(
        &mut self,
        time_s: f64,
        origin: Vec3,
        dirs: &[Vec3],
    ) -> Result<Vec<Option<(f32, usize)>>, RenderError> {
        check_time(time_s)?;
        let world = self.world.as_mut().ok_or(RenderError::NoScene)?;
        self.pool.install(|| world.set_time(time_s))?;
        Ok(dirs
            .iter()
            .map(|&dir| {
                let ray = ray::Ray::new(origin.into(), Vec3A::from(dir));
                world
                    .closest_hit(&ray)
                    .map(|hit| (hit.t, world.object_of(hit.prim) as usize))
            })
            .collect())
    }

    /// The history's picture as `camera` sees it ([`Renderer::present_warped`]).
    fn warp(&mut self, camera: &Camera) -> Result<Picture, RenderError> {
        check_camera(camera)?;
        let history = self.history.as_mut().ok_or_else(|| {
            RenderError::Unavailable(
                "a warped refresh needs the temporal mode (its history and geometry)".into(),
            )
        })?;
        let size = history.clock.settings();
        self.pool
            .install(|| history.warped(&camera.frame(size.width, size.height)))
            .ok_or(RenderError::NoFrame)
    }
}

/// The picture of a `width` × `height` image whose pixel i is `rgb(i)`, tone-mapped as
/// [`Image::to_srgb8_rgba`] does, a row at a time on the current rayon pool.
fn tone_mapped(width: u32, height: u32, rgb: impl Fn(usize) -> [f32; 3] + Sync) -> Picture {
    let row = width as usize;
    let mut rgba = vec![255u8; 4 * row * height as usize];
    rgba.par_chunks_mut(4 * row)
        .enumerate()
        .for_each(|(y, out)| {
            for (x, pixel) in out.chunks_exact_mut(4).enumerate() {
                for (channel, c) in pixel.iter_mut().zip(rgb(y * row + x)) {
                    *channel = linear_to_srgb8_fast(c);
                }
            }
        });
    Picture {
        width,
        height,
        rgba,
    }
}

impl Renderer for CpuRenderer {
    fn info(&self) -> BackendInfo {
        let model = device::cpu_model().unwrap_or_else(|| "unknown CPU".to_string());
        BackendInfo {
            backend: "cpu".to_string(),
            device: format!("{model} ({} threads)", self.threads()),
        }
    }

    fn load_scene(&mut self, scene: &Scene) -> Result<(), RenderError> {
        self.world = Some(World::new(scene)?);
        self.reset_history();
        Ok(())
    }

    fn render(
        &mut self,
        camera: &Camera,
        time_s: f64,
        settings: &RenderSettings,
    ) -> Result<FrameStats, RenderError> {
        settings.validate()?;
        check_time(time_s)?;
        check_camera(camera)?;
        let world = self.world.as_mut().ok_or(RenderError::NoScene)?;
        let (width, height) = (settings.width, settings.height);
        if let Some(history) = &self.history {
            history.clock.settings().check(settings)?;
        }
        if self.budget.is_some() && self.history.is_some() {
            return Err(budget_in_temporal_mode());
        }
        self.warped = None;
        let start = Instant::now();
        let accel_ms = self.pool.install(|| world.set_time(time_s))?;
        let world = &*world;
        let mut spp = settings.spp;
        let counts = match &mut self.history {
            None => {
                let image = match &mut self.image {
                    Some(img) if img.width == width && img.height == height => img,
                    slot => slot.insert(Image::new(width, height)),
                };
                let frame = camera.frame(width, height);
                let outputs = FrameOutputs {
                    pixels: &mut image.pixels,
                    geometry: None,
                };
                let (jitter, sample_base) = self.stream.pattern();
                let pattern = SamplePattern {
                    jitter,
                    sample_base,
                    still_frame: 0,
                };
                match &self.budget {
                    None => self.pool.install(|| {
                        render::render_frame(world, &frame, settings, pattern, outputs)
                    }),
                    Some(budget) => {
                        let elapsed_ms = || start.elapsed().as_secs_f64() * 1e3;
                        let counts = self.pool.install(|| {
                            render::render_frame_within(
                                world,
                                &frame,
                                settings,
                                pattern,
                                outputs.pixels,
                                budget,
                                elapsed_ms,
                            )
                        });
                        // The mean over the frame's pixels: the units' groups cover
                        // shares of an image that differ a little from a sixteenth.
                        let eye_rays = counts.ray_counts(0).per_depth[0];
                        spp = (eye_rays as f64 / settings.pixels() as f64) as f32;
                        counts
                    }
                }
            }
            Some(history) => {
                // Rays follow the history's aspect, so every sample lies where it lands.
                let size = history.clock.settings();
                let frame = camera.frame(size.width, size.height);
                let temporal =
                    history
                        .clock
                        .advance(frame, time_s, world.is_animated(), settings.spp);
                if temporal.world_moved {
                    world.surface_moves(temporal.previous_time_s, time_s, &mut history.moves);
                }
                let pattern = SamplePattern {
                    jitter: temporal.jitter,
                    sample_base: sample_base(temporal.index),
                    still_frame: temporal.still_frame(),
                };
                history.prepare(width, height);
                self.pool.install(|| {
                    let outputs = FrameOutputs {
                        pixels: &mut history.low,
                        geometry: Some(&mut history.low_geometry),
                    };
                    let counts = render::render_frame(world, &frame, settings, pattern, outputs);
                    history.resolve(frame, temporal, (width, height));
                    counts
                })
            }
        };
        let rays = counts.ray_counts(settings.max_depth);
        let ms = start.elapsed().as_secs_f64() * 1e3;
        Ok(FrameStats {
            render_ms: ms,
            accel_ms,
            wall_ms: ms,
            timing: TimingSource::WallClock,
            samples: rays.per_depth[0],
            spp,
            rays,
            width,
            height,
        })
    }

    fn read_image(&mut self) -> Result<Image, RenderError> {
        match &self.history {
            Some(history) => history.image().ok_or(RenderError::NoFrame),
            None => self.image.clone().ok_or(RenderError::NoFrame),
        }
    }

    fn present(&mut self) -> Result<Presented, RenderError> {
        self.warped = None;
        Ok(Presented::Host(self.read_picture()?))
    }

    fn read_picture(&mut self) -> Result<Picture, RenderError> {
        if let Some(camera) = self.warped {
            return self.warp(&camera);
        }
        let pool = &self.pool;
        match &self.history {
            Some(history) => pool
                .install(|| history.picture())
                .ok_or(RenderError::NoFrame),
            None => {
                let image = self.image.as_ref().ok_or(RenderError::NoFrame)?;
                let pixels = &image.pixels;
                Ok(pool.install(|| tone_mapped(image.width, image.height, |i| pixels[i])))
            }
        }
    }

    fn present_warped(&mut self, camera: &Camera) -> Result<Presented, RenderError> {
        let picture = self.warp(camera)?;
        self.warped = Some(*camera);
        Ok(Presented::Host(picture))
    }

    fn set_temporal(&mut self, temporal: Option<TemporalSettings>) -> Result<(), RenderError> {
        if let Some(settings) = &temporal {
            settings.validate()?;
        }
        self.history = temporal.map(History::new);
        self.warped = None;
        Ok(())
    }

    fn reset_history(&mut self) {
        if let Some(history) = &mut self.history {
            history.clock.reset();
        }
    }

    fn set_sample_stream(&mut self, stream: SampleStream) {
        self.stream = stream;
    }

    fn set_frame_budget(&mut self, budget: Option<FrameBudget>) -> Result<(), RenderError> {
        if budget.is_some() && self.history.is_some() {
            return Err(budget_in_temporal_mode());
        }
        self.budget = budget;
        Ok(())
    }
}

/// Why a frame budget is refused in the temporal mode.
fn budget_in_temporal_mode() -> RenderError {
    RenderError::Unavailable(
        "a frame budget needs plain frames: the temporal mode weighs each frame into its \
         history by the S planned before it is rendered"
            .into(),
    )
}
