//! Frame-time controllers for real-time rendering, after Ishii and Shida's constant frame rate
//! control for real-time ray tracing, with a simulated renderer to test them and the
//! benchmark's metrics.
//!
//! The controller sees numbers only (frame time Tp, rays traced per depth, pixels, the quality
//! used) and returns the next frame's [`Quality`]: S (eye rays per pixel, fractional allowed),
//! R (reflection/refraction depth) and the resolution scale. It knows nothing about rendering.
//!
//! ```
//! use steadyray_control::{Band, Bounds, Controller, Setup, from_name, simulate, metrics};
//!
//! let bounds = Bounds::default();
//! let setup = Setup::new(Band::new(15.0, 20.0)?, bounds, bounds.max_quality())?;
//! let mut c = from_name("predictive", setup, "")?;
//! let model = simulate::RendererModel::corridor(720);
//! let records = simulate::run(c.as_mut(), &model, 720);
//! let s = metrics::summarize(&records[20..], setup.band, bounds.max_quality(), None);
//! assert!(s.ok_pct > 99.0); // in the band, or under it at the highest quality
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Controllers ([`from_name`] builds one by name, with `key=value` options)
//!
//! - `fixed` ([`Fixed`]): no control; the starting quality every frame. `spp`, `depth` and
//!   `scale` set another quality to hold (inside the bounds), e.g. `spp=4 depth=16`.
//! - `step` ([`Step`]): the paper's rule. Tp > Tmax: one step down; Tp < Tmin: one step up;
//!   in the band: nothing. `knob=depth` (default) | `spp` | `both` (cuts S first down to its
//!   minimum, then R; raises R first up to its maximum, then S). Steps are ±1 on whole
//!   numbers, which reproduces the paper's oscillation across a narrow band.
//! - `hysteresis` ([`Hysteresis`]): cut fast, raise slowly, as games' dynamic resolution
//!   does. Cuts at once when Tp > Tmax (proportionally to the overshoot: nominal work ×
//!   target/Tp), or after `cut_after`=1 frame above Tmin + `cut_above`=0.8 of the band;
//!   raises after `up_after`=3 frames below Tmin + `raise_below`=0.3 of the band, by at most
//!   `max_up`=30 % of nominal work; `min_interval`=3 frames between changes (overloads
//!   excepted); a frame over Tmax and `hitch_ratio`=3 times the previous one is held unless
//!   the next frame confirms it, and a first frame over Tmax after frames under the soft
//!   limit cuts no further than would land the frame before it at the target (a spike's
//!   cut). `target`=0.4 (below the centre: headroom for rising loads);
//!   `order`=depth,scale,spp.
//! - `predictive` ([`Predictive`]): fits Tp ≈ fixed_ms + ms_per_ray · rays online
//!   ([`cost_model`]: exponential forgetting `forgetting`=0.95, outliers beyond
//!   `outlier_k`=4 robust deviations set aside, spikes over Tmax included, `confirm`=2
//!   outliers on one side confirm a real cost change), predicts each candidate's rays from
//!   the last frame's rays per depth ([`ray_model`]), extrapolates the load's trend
//!   (`trend`=0.5), and keeps the quality while the prediction lies inside the inner band
//!   (`deadband`=0.2 of the band from each side until the noise is measured, then around a
//!   target placed by the measured noise, as narrow as its scatter allows: 0.12 of the band
//!   on each side on a quiet machine);
//!   otherwise it takes the highest quality predicted to fit the target (`target`=0.5),
//!   raising at most `max_raise`=2× the rays per change. Raising order (`order`): R while
//!   at least `min_reach`=2 % of eye rays reach the deeper level (all of R when the deeper
//!   levels together carry under that), then scale, then S, then the remaining R; cuts in
//!   reverse (S goes first, resolution next). `ladder`=PATH: move
//!   along a calibrated Pareto front of (S, R, scale) settings instead ([`ladder`]).
//! - `perceptual` ([`Perceptual`]): chooses the frame time too. From a quality model over
//!   (screen speed, frame time, ladder point) ([`motion_model`]: the one shipped with the
//!   crate, or `model`=PATH, measured on the scene by `calibrate --motion`) it picks, at each frame's measured speed, the frame time whose
//!   best fitting ladder point looks best, and lets an inner `predictive` hold that time;
//!   changes of the target are held `hold_ms`=500 and need a `margin`=0.02 of the model's
//!   spread; the speed decided on falls with a time constant `fall_ms`=300. `hand_over`=1 ms,
//!   `slack`=0.05 and `width`=0.2 shape each frame time's band (as `bench --band refresh`);
//!   the other options are `predictive`'s.
//!
//! # Refused reports
//!
//! A report whose Tp is NaN, infinite, zero, negative or over [`MAX_FRAME_MS`] (one minute)
//! is refused by every controller: `observe` returns a [`ReportError`] and nothing changes
//! (quality, history and models), so one bad timer reading never poisons a run. `predictive`
//! also refuses reports without pixels or eye rays ([`ReportError::NoRays`]), and
//! `perceptual` a screen speed that is NaN, infinite or negative ([`ReportError::BadSpeed`]).
//!
//! # Testing without a GPU
//!
//! [`simulate`] is a renderer on a fake clock (cost model, corridor-shaped load, noise,
//! spikes, a 1 ms timer), which can replay a real machine's recorded timing noise
//! ([`noise`]: jitter, spikes and spells, fitted from fixed-quality runs); [`metrics`]
//! computes the benchmark's figures from any run, and [`aim_ceiling()`] the most frames any
//! one planned frame time could have kept in the band against a run's prediction errors.

pub mod aim_ceiling;
pub mod band;
pub mod budget;
pub mod controller;
pub mod cost_model;
pub mod decision;
pub mod error;
pub mod fixed;
pub mod hysteresis;
pub mod ladder;
pub mod metrics;
pub mod motion_model;
pub mod noise;
pub mod options;
pub mod perceptual;
pub mod predictive;
pub mod quality;
pub mod ray_model;
pub mod report;
pub mod simulate;
pub mod spec;
pub mod step;

pub use aim_ceiling::{AimCeiling, aim_ceiling};
pub use band::{Band, Position};
pub use budget::{FirstSample, FrameBudget};
pub use controller::{
    CONTROLLER_NAMES, Controller, DisplayCosts, NoFiles, OptionFiles, Setup, from_name,
    from_name_with, parse_options,
};
pub use decision::{Action, Decision, Reason};
pub use error::{ConfigError, Error};
pub use fixed::Fixed;
pub use hysteresis::{Hysteresis, HysteresisParams};
pub use ladder::{Ladder, LadderPoint, pareto_front};
pub use metrics::{FrameRecord, RunSummary, most_in_band_fixed, summarize};
pub use motion_model::{Metric, MotionModel};
pub use noise::{NoiseProcess, NoiseProfile, fit_profile};
pub use perceptual::{Perceptual, PerceptualParams, Prospect};
pub use predictive::{Aim, Predictive, PredictiveParams};
pub use quality::{Bounds, Knob, KnobOrder, Quality};
pub use report::{FrameReport, MAX_FRAME_MS, ReportError};
pub use spec::{ControllerSpec, SpecError, parse_controllers};
pub use step::{Step, StepKnob, StepParams};
