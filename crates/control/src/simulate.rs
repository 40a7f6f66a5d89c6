//! A simulated renderer on a fake clock, to test controllers deterministically.
//!
//! Cost model: Tp = (fixed_ms + ns_per_ray · rays · cost_factor) · noise · spike, measured
//! by a timer of `timer_ms` resolution (the paper's 1 ms). Rays come from pixels, S, R and
//! the frame's [`Load`]: the fraction of eye rays reaching each depth and the shadow rays per
//! ray. Noise is multiplicative and Gaussian; spikes (hitches) multiply a frame's time by
//! `spike_factor`, at random with `spike_prob` or on the frames listed in `spike_frames`.
//! A recorded machine's noise ([`crate::noise`]: jitter, spikes and spells of slower and
//! faster speed) multiplies it further when the model carries a [`NoiseProfile`].
//! Everything random comes from a seeded PCG generator that draws the same numbers every
//! frame whatever the controller does, so runs are reproducible and comparable.

use crate::budget::FirstSample;
use crate::budget::{FrameBudget, spp_of_units, units_for_spp};
use crate::controller::Controller;
use crate::metrics::FrameRecord;
use crate::noise::{NoiseProcess, NoiseProfile};
use crate::quality::Quality;
use crate::report::FrameReport;
use std::cell::Cell;
use std::f64::consts::TAU;

/// The deepest level a simulated load describes.
pub const SIM_MAX_DEPTH: usize = 64;

/// What one frame's view costs, independent of quality.
#[derive(Clone, Debug, PartialEq)]
pub struct Load {
    /// `reach[k]`: the fraction of eye rays that reach depth k (`reach[0]` = 1); depths
    /// beyond the vector are not reached.
    pub reach: Vec<f64>,
    /// Shadow rays per eye ray.
    pub shadow_eye: f64,
    /// Shadow rays per secondary (reflected or refracted) ray.
    pub shadow_bounce: f64,
    /// Multiplies the cost per ray (heavier shading or traversal); 1 normally.
    pub cost_factor: f64,
}

impl Load {
    /// A load where `first` of the eye rays bounce once and each further level keeps
    /// `decay` of the previous one.
    pub fn geometric(first: f64, decay: f64, shadow_eye: f64, shadow_bounce: f64) -> Self {
        let mut reach = vec![1.0, first];
        while reach.len() <= SIM_MAX_DEPTH {
            reach.push(reach[reach.len() - 1] * decay);
        }
        Self {
            reach,
            shadow_eye,
            shadow_bounce,
            cost_factor: 1.0,
        }
    }

    /// This load with the cost per ray multiplied by `factor`.
    pub fn with_cost_factor(mut self, factor: f64) -> Self {
        self.cost_factor *= factor;
        self
    }

    /// Rays at level k for `eye` eye rays.
    fn level(&self, eye: f64, k: usize) -> u64 {
        (eye * self.reach.get(k).copied().unwrap_or(0.0)).round() as u64
    }

    /// Rays per depth and shadow rays for `eye` eye rays and depth R.
    fn rays(&self, eye: f64, depth: u32) -> (Vec<u64>, u64) {
        let per_depth: Vec<u64> = (0..=depth as usize).map(|k| self.level(eye, k)).collect();
        let secondary: u64 = per_depth.iter().skip(1).sum();
        let shadow = per_depth[0] as f64 * self.shadow_eye + secondary as f64 * self.shadow_bounce;
        (per_depth, shadow.round() as u64)
    }

    /// This load with a swarm of objects in view (the world changing, not the camera):
    /// `coverage` of the eye rays now hit a swarm object, which sends `bounce` of them on as
    /// a mirror would (they then go on as the load's first bounces do) and each takes a
    /// shadow ray per light (`lights`); and the scene holds `object_factor` times the
    /// objects, so each ray's BVH traversal costs more by the depth of the tree, which grows
    /// as the logarithm of the object count: the cost per ray is multiplied by
    /// 1 + log2(object_factor) / `tree_depth` (`tree_depth` the levels of the tree before).
    pub fn with_swarm(
        mut self,
        coverage: f64,
        bounce: f64,
        lights: f64,
        object_factor: f64,
        tree_depth: f64,
    ) -> Self {
        let extra = coverage * bounce;
        let first = self.reach.get(1).copied().unwrap_or(0.0);
        // The rays the swarm sends on continue as the load's own first bounces do.
        let keep: Vec<f64> = self
            .reach
            .iter()
            .map(|&r| if first > 0.0 { r / first } else { 0.0 })
            .collect();
        for (k, r) in self.reach.iter_mut().enumerate().skip(1) {
            let follow = if k == 1 { 1.0 } else { keep[k] };
            *r = (*r + extra * follow).min(1.0);
        }
        self.shadow_eye += coverage * lights;
        self.cost_factor *= 1.0 + object_factor.max(1.0).log2() / tree_depth.max(1.0);
        self
    }

    /// Rays per eye sample at depth R, shadows included: the load's weight at that depth.
    pub fn rays_per_sample(&self, depth: u32) -> f64 {
        let (per_depth, shadow) = self.rays(1e6, depth);
        (per_depth.iter().sum::<u64>() + shadow) as f64 / 1e6
    }
}

/// The load of the `corridor` scene (docs/corridor.md) at camera yaw θ, modelled: around
/// θ = 0 the mirrors fill the sides of the view and rays bounce between them (a ray that hit
/// a mirror hits the other one with probability up to 0.95, a little less at each level as
/// rays leave the corridor's ends); around θ = ±π/2 almost nothing is drawn; around θ = π the
/// diffuse spheres behind the camera are in view (hits but no bounces).
pub fn corridor_load(theta: f64) -> Load {
    let front = theta.cos().max(0.0);
    let back = (-theta.cos()).max(0.0);
    let mirror = 0.85 * front.powf(1.5);
    let keep = 0.75 + 0.2 * front;
    let mut reach = vec![1.0, mirror];
    while reach.len() <= SIM_MAX_DEPTH {
        let k = reach.len() as f64;
        reach.push(reach[reach.len() - 1] * keep * (1.0 - k / 48.0).max(0.0));
    }
    let eye_hits = 0.03 + 0.12 * front + mirror + 0.35 * back * back;
    Load {
        reach,
        shadow_eye: 2.0 * eye_hits.min(1.0),
        shadow_bounce: 1.8,
        cost_factor: 1.0,
    }
}

/// The load of each frame of a run.
#[derive(Clone, Debug, PartialEq)]
pub enum LoadProfile {
    /// The same load every frame.
    Constant(Load),
    /// `before` until frame `at`, then `after` (a sudden change, e.g. 2x the rays).
    Step {
        /// The load up to frame `at`.
        before: Load,
        /// The load from frame `at` on.
        after: Load,
        /// The first frame of `after`.
        at: usize,
    },
    /// `during` from frame `from` until (not including) frame `until`, `base` before and
    /// after: objects that appear at once and vanish again (a swarm, see
    /// [`Load::with_swarm`]).
    Interval {
        /// The load outside the interval.
        base: Load,
        /// The load inside it.
        during: Load,
        /// The first frame of `during`.
        from: usize,
        /// The first frame after it.
        until: usize,
    },
    /// The corridor sweep: frame k of `frames` has yaw θ = 2π·k/frames.
    Corridor {
        /// Frames in one turn of the sweep.
        frames: usize,
    },
    /// One load per frame (repeated cyclically).
    Frames(Vec<Load>),
}

impl LoadProfile {
    /// A load step whose later load traces `factor` times the rays of `before` at depth R
    /// (more mirrors in view: more eye rays bounce), at frame `at`.
    pub fn ray_step(before: Load, factor: f64, depth: u32, at: usize) -> Self {
        let base = before.rays_per_sample(depth);
        // Raise the reach of every level k >= 1 by a common factor c solving the weight.
        let (mut lo, mut hi) = (1.0, 1e3);
        for _ in 0..100 {
            let c = 0.5 * (lo + hi);
            let mut l = before.clone();
            l.reach
                .iter_mut()
                .skip(1)
                .for_each(|r| *r = (*r * c).min(1.0));
            if l.rays_per_sample(depth) < factor * base {
                lo = c;
            } else {
                hi = c;
            }
        }
        let mut after = before.clone();
        after
            .reach
            .iter_mut()
            .skip(1)
            .for_each(|r| *r = (*r * lo).min(1.0));
        Self::Step { before, after, at }
    }

    /// The load of frame `frame`.
    pub fn load(&self, frame: usize) -> Load {
        match self {
            Self::Constant(l) => l.clone(),
            Self::Step { before, after, at } => {
                if frame < *at {
                    before.clone()
                } else {
                    after.clone()
                }
            }
            Self::Interval {
                base,
                during,
                from,
                until,
            } => {
                if (*from..*until).contains(&frame) {
                    during.clone()
                } else {
                    base.clone()
                }
            }
            Self::Corridor { frames } => {
                corridor_load(TAU * frame as f64 / (*frames).max(1) as f64)
            }
            Self::Frames(v) => v[frame % v.len().max(1)].clone(),
        }
    }

    /// The frames where the load changes suddenly (for [`crate::metrics::summarize`]): the
    /// step's frame, an interval's two ends, or where the weight at depth 8 changes by 1.5x
    /// or more between frames.
    pub fn changes(&self, frames: usize) -> Vec<usize> {
        match self {
            Self::Constant(_) | Self::Corridor { .. } => Vec::new(),
            Self::Step { at, .. } => (*at < frames).then_some(*at).into_iter().collect(),
            Self::Interval { from, until, .. } => [*from, *until]
                .into_iter()
                .filter(|&f| f < frames)
                .collect(),
            Self::Frames(_) => (1..frames)
                .filter(|&i| {
                    let (a, b) = (
                        self.load(i - 1).rays_per_sample(8),
                        self.load(i).rays_per_sample(8),
                    );
                    a.max(b) >= 1.5 * a.min(b)
                })
                .collect(),
        }
    }
}

/// The simulated renderer's parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct RendererModel {
    /// Pixels at scale 1.
    pub full_pixels: u64,
    /// Fixed cost per frame, ms.
    pub fixed_ms: f64,
    /// Cost per ray, ns.
    pub ns_per_ray: f64,
    /// Standard deviation of the multiplicative Gaussian noise (0.04: 4 %).
    pub noise: f64,
    /// Probability that a frame is a spike.
    pub spike_prob: f64,
    /// A spike multiplies the frame's time by this.
    pub spike_factor: f64,
    /// Frames that are always spikes.
    pub spike_frames: Vec<usize>,
    /// Timer resolution, ms (0: exact).
    pub timer_ms: f64,
    /// Seed of the random generator.
    pub seed: u64,
    /// The load of each frame.
    pub profile: LoadProfile,
    /// The screen speed each frame reports, deg/s, by frame (repeated cyclically; empty: a
    /// still picture, 0).
    pub speed_deg_s: Vec<f64>,
    /// A recorded machine's noise replayed on top of `noise` and the spikes (`None`: none),
    /// from its own generator seeded by `seed`, so a model without it draws as before.
    pub machine_noise: Option<NoiseProfile>,
}

impl RendererModel {
    /// The tuned corridor model: 640×360 pixels, 1 ms + 0.15 ns per ray, 4 % noise, a 1 ms
    /// timer, no spikes. At the highest default quality (S 256, R 16, scale 1) a frame takes
    /// about 10 ms at θ = ±π/2 (under a [15, 20] band), 17 ms at θ = π and 200 ms at θ = 0.
    pub fn corridor(frames: usize) -> Self {
        Self {
            full_pixels: 640 * 360,
            fixed_ms: 1.0,
            ns_per_ray: 0.15,
            noise: 0.03,
            spike_prob: 0.0,
            spike_factor: 10.0,
            spike_frames: Vec::new(),
            timer_ms: 1.0,
            seed: 1,
            profile: LoadProfile::Corridor { frames },
            speed_deg_s: Vec::new(),
            machine_noise: None,
        }
    }

    /// The corridor model with another load profile.
    pub fn with_profile(self, profile: LoadProfile) -> Self {
        Self { profile, ..self }
    }

    /// The model with frames reporting these screen speeds (deg/s, by frame, cyclic).
    pub fn with_speeds(self, speed_deg_s: Vec<f64>) -> Self {
        Self {
            speed_deg_s,
            ..self
        }
    }

    /// The model with a recorded machine's noise (see [`crate::noise`]) replayed on its frames.
    pub fn with_machine_noise(self, profile: NoiseProfile) -> Self {
        Self {
            machine_noise: Some(profile),
            ..self
        }
    }

    /// The screen speed frame `frame` reports, deg/s.
    pub fn speed_at(&self, frame: usize) -> f64 {
        match self.speed_deg_s.len() {
            0 => 0.0,
            n => self.speed_deg_s[frame % n],
        }
    }

    /// The noise-free time of a frame at quality `q` under `load`, ms.
    pub fn ideal_ms(&self, q: &Quality, load: &Load) -> f64 {
        let (rays, shadow) = load.rays(self.eye_rays(q), q.depth);
        let total = rays.iter().sum::<u64>() + shadow;
        self.fixed_ms + self.ns_per_ray * 1e-6 * total as f64 * load.cost_factor
    }

    /// The quality a frame planned at `q` reaches within `budget` when the frame's times
    /// are `factor` times the noise-free ones: its S as [`FrameBudget::run_units`] decides.
    fn budgeted_quality(
        &self,
        budget: &FrameBudget,
        load: &Load,
        q: Quality,
        factor: f64,
    ) -> Quality {
        let at = |spp: f32| self.ideal_ms(&Quality { spp, ..q }, load) * factor;
        let units = Cell::new(0);
        let done = budget.run_units(
            units_for_spp(q.spp),
            || at(spp_of_units(units.get())),
            |batch| units.set(batch.end),
        );
        Quality {
            spp: spp_of_units(done),
            ..q
        }
    }

    fn pixels(&self, q: &Quality) -> u64 {
        let s = f64::from(q.scale);
        ((self.full_pixels as f64 * s * s).round() as u64).max(1)
    }

    fn eye_rays(&self, q: &Quality) -> f64 {
        (self.pixels(q) as f64 * f64::from(q.spp)).round()
    }
}

/// A tiny PCG-XSH-RR 32-bit generator (O'Neill 2014): deterministic, seedable, no crates.
#[derive(Clone, Debug)]
pub struct Pcg32 {
    state: u64,
    inc: u64,
}

impl Pcg32 {
    /// A generator from a seed.
    pub fn new(seed: u64) -> Self {
        let mut g = Self {
            state: 0,
            inc: (seed << 1) | 1,
        };
        g.next_u32();
        g.state = g.state.wrapping_add(0x853c_49e6_748f_ea9b ^ seed);
        g.next_u32();
        g
    }

    /// The next 32 random bits.
    pub fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = old
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(self.inc);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        xorshifted.rotate_right((old >> 59) as u32)
    }

    /// A uniform number in [0, 1).
    pub fn unit(&mut self) -> f64 {
        f64::from(self.next_u32()) / 4_294_967_296.0
    }

    /// A standard normal number (Box–Muller; always draws two uniforms).
    pub fn normal(&mut self) -> f64 {
        let u1 = 1.0 - self.unit();
        let u2 = self.unit();
        (-2.0 * u1.ln()).sqrt() * (TAU * u2).cos()
    }
}

/// The simulated renderer: a [`RendererModel`] with its fake clock and random state.
#[derive(Clone, Debug)]
pub struct SimRenderer {
    model: RendererModel,
    clock_ms: f64,
    rng: Pcg32,
    machine: Option<NoiseProcess>,
    /// When the last frame started on the fake clock, ms.
    last_start_ms: f64,
}

/// Mixed into the seed of the machine noise's generator, so it draws apart from the model's.
const MACHINE_SEED: u64 = 0x6d61_6368_696e_6531;

impl SimRenderer {
    /// A renderer at time 0.
    pub fn new(model: RendererModel) -> Self {
        let rng = Pcg32::new(model.seed);
        let machine = model
            .machine_noise
            .clone()
            .map(|p| NoiseProcess::new(p, model.seed ^ MACHINE_SEED));
        Self {
            model,
            clock_ms: 0.0,
            rng,
            machine,
            last_start_ms: 0.0,
        }
    }

    /// The model it simulates.
    pub fn model(&self) -> &RendererModel {
        &self.model
    }

    /// "Renders" frame `frame` at quality `q`: the report a real renderer would give.
    pub fn render(&mut self, frame: usize, q: Quality) -> FrameReport {
        let load = self.model.profile.load(frame);
        self.render_load(frame, &load, q)
    }

    /// "Renders" the `frame`-th frame of a run (spikes listed by frame still apply) with the
    /// view's cost given by `load` instead of the profile: a path followed in time rather than
    /// frame by frame (e.g. [`corridor_load`] at the yaw of a time).
    pub fn render_load(&mut self, frame: usize, load: &Load, q: Quality) -> FrameReport {
        self.render_within(frame, load, q, None)
    }

    /// [`SimRenderer::render_load`] within a frame's time `budget`, when given: the frame
    /// takes its samples as a progressive renderer does ([`FrameBudget::run_units`]: the
    /// first sample of every pixel, then units of pairs), each part costing its share of
    /// the frame's rays at the frame's noise, and reports the S it reached.
    pub fn render_within(
        &mut self,
        frame: usize,
        load: &Load,
        q: Quality,
        budget: Option<&FrameBudget>,
    ) -> FrameReport {
        let m = &self.model;
        let noise = (1.0 + m.noise * self.rng.normal()).max(0.1);
        let spike_draw = self.rng.unit();
        let gap = self.rng.unit();
        let spike = spike_draw < m.spike_prob || m.spike_frames.contains(&frame);
        let start = self.clock_ms;
        let machine = self
            .machine
            .as_mut()
            .map_or(1.0, |n| n.factor(start - self.last_start_ms));
        self.last_start_ms = start;
        let factor = noise * machine * if spike { m.spike_factor } else { 1.0 };
        let planned = q;
        let q = match budget {
            Some(budget) => m.budgeted_quality(budget, load, q, factor),
            None => q,
        };
        let first_sample = budget.map(|_| {
            let first = Quality {
                spp: 1.0,
                ..planned
            };
            let (rays, shadow) = load.rays(m.eye_rays(&first), first.depth);
            FirstSample {
                rays: rays.iter().sum::<u64>() + shadow,
                ms: m.ideal_ms(&first, load) * factor,
            }
        });
        let eye = m.eye_rays(&q);
        let (rays_per_depth, shadow_rays) = load.rays(eye, q.depth);
        let true_ms = m.ideal_ms(&q, load) * factor;
        let end = start + true_ms;
        let tp_ms = if m.timer_ms > 0.0 {
            ((end / m.timer_ms).floor() - (start / m.timer_ms).floor()) * m.timer_ms
        } else {
            true_ms
        };
        // The time between frames (present, input) puts the next start at a random phase.
        self.clock_ms = end + 2.0 + gap;
        FrameReport {
            tp_ms,
            rays_per_depth,
            shadow_rays,
            rays_stopped: Some(load.level(eye, q.depth as usize + 1)),
            pixels: m.pixels(&q),
            quality: q,
            speed_deg_s: m.speed_at(frame),
            first_sample,
        }
    }
}

/// Runs `controller` for `frames` frames on a fresh renderer of `model`, from the
/// controller's current quality. Refused reports (e.g. a 0 ms frame from the coarse timer)
/// are still recorded. Returns one record per frame.
pub fn run(
    controller: &mut dyn Controller,
    model: &RendererModel,
    frames: usize,
) -> Vec<FrameRecord> {
    let mut renderer = SimRenderer::new(model.clone());
    (0..frames)
        .map(|frame| {
            let q = controller.quality();
            let load = renderer.model.profile.load(frame);
            let budget = controller.frame_budget();
            let report = renderer.render_within(frame, &load, q, budget.as_ref());
            // A refused report leaves the controller unchanged; the record keeps the frame.
            let _ = controller.observe(&report);
            FrameRecord {
                frame,
                tp_ms: report.tp_ms,
                quality: q,
                rays: report.total_rays(),
            }
        })
        .collect()
}
