//! `perceptual`: chooses the frame rate and the image quality together, by what the viewer
//! will see at the speed the picture moves.
//!
//! After Denes, Jindal, Mikhailiuk and Mantiuk (*A perceptual model of motion quality for
//! rendering with adaptive refresh-rate and resolution*, SIGGRAPH 2020): fast motion on
//! screen calls for short frames (judder and hold blur dominate), slow motion for a better
//! picture at a lower rate. A [`MotionModel`] scores (speed, frame time, ladder point);
//! each frame this controller
//!
//! 1. lets an inner [`Predictive`] controller on the model's ladder take the frame (its cost
//!    and ray models, its cuts on overload) and keep the current target's band;
//! 2. asks, for every frame time T the model knows, where on the ladder the predictive
//!    controller would settle with T as its target ([`Predictive::ladder_position_within`]
//!    at the aim of T's band), and what the model scores that at the frame's measured speed
//!    ([`FrameReport::speed_deg_s`]);
//!    The speed it decides on rises at once with the measured one and falls slowly
//!    (`fall_ms`: it decays toward a lower measured speed with that time constant), so a
//!    fast turn gets short frames from its first frame and a speed jittering across the
//!    point where two frame times score the same does not switch between them;
//! 3. moves the target to the best frame time, hysteretically: only when it scores more than
//!    `margin` (a fraction of the table's spread) above the current one; to a shorter frame
//!    time at once (motion that asks for it has begun, and each frame held longer shows it
//!    juddering), to a longer one only `hold_ms` of display time (counted as each frame's
//!    target time) after the last change, so the rate does not flicker between two refresh
//!    multiples. A target none of whose settings fits any more (the model's cheapest point
//!    at the lowest resolution scale, [`crate::ladder::LADDER_FLOOR`], predicted over its
//!    band) gives way at once. Below the cheapest point the model's utility is extrapolated
//!    by the rays saved ([`MotionModel::utility_below`]), so a shorter frame time reached
//!    only at lower resolution is weighed against a longer one at a better setting; only
//!    when the model's stimuli were shown as the frames are, warped or not
//!    ([`Perceptual::trusts_below_ladder`]), else such a frame time counts as not fitting.
//!
//! The band for a frame time T of M refreshes of the model's display (so that a frame started
//! at a refresh is handed over before the refresh T later, with `slack` of T kept free for
//! timing noise, and the M − 1 refreshes between frames warped on the same machine under
//! `bench --warp`) is `steadyray_display::shaped_band` with margin `slack` and width `width`:
//! the band of `bench --band refresh[:M]` (`aligned_band`) at the defaults. The model's scores
//! are of frames held for T, or warped between (`calibrate --motion --warp`). The setup's
//! band is not used: the bands come from the model's frame times. The target starts at the longest
//! frame time (a still picture is best shown at the highest quality).
//!
//! Why a controller of its own and not a target mode of `predictive`: the choice of a frame
//! time needs a model of the viewer and the speed on screen, which `predictive` (a band
//! holder any engine can use without either) should not carry; composed, the frame-time
//! choice sits on top of the one cost model, and `predictive` keeps the chosen time exactly
//! as it keeps any band.
//!
//! Out of the box (no `model`) it uses the model that ships with the crate,
//! [`MotionModel::shipped`]: one generic ladder and the mean of models calibrated on scenes
//! other than the scene suite's (`docs/default-motion-model.md`). Whatever the model, the
//! ladder points it scores no better than a cheaper one at every speed and frame time are
//! left out ([`MotionModel::without_dominated_points`]). A model calibrated on the
//! scene itself (`calibrate`, then `calibrate --motion`) may choose better; the suite
//! measures how much (`perceptual` against `perceptual-scene`, `docs/scene-suite.md`).
//!
//! Options: `model`=PATH (a `motion.json` from `calibrate --motion`; default the shipped one),
//! `hold_ms`=500, `margin`=0.02, `fall_ms`=300, `hand_over`=1 (ms), `warp`=0 (ms), `slack`=0.05,
//! `width`=0.2, and every option of
//! `predictive` but `ladder` (the ladder is the model's).

use crate::band::Band;
use crate::budget::FrameBudget;
use crate::controller::{Controller, DisplayCosts, Setup, parse_option, within};
use crate::decision::Decision;
use crate::error::ConfigError;
use crate::motion_model::MotionModel;
use crate::predictive::{Predictive, PredictiveParams};
use crate::quality::Quality;
use crate::report::{FrameReport, ReportError};
use steadyray_display::{BandShape, DisplayConfig, SyncMode, shaped_band};

/// Parameters of [`Perceptual`], with their option names and defaults.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct PerceptualParams {
    /// `model`: the quality model (a `motion.json`). Default (`None`): the shipped one,
    /// [`MotionModel::shipped`].
    pub model: Option<MotionModel>,
    /// `hold_ms`: display time (ms, each frame counted at its target time) from a change of
    /// the target to a move to a longer frame time; a move to a shorter one is taken at once.
    /// Default 500.
    pub hold_ms: f64,
    /// `margin`: how much better another frame time must score to be taken, as a fraction
    /// of the model's spread of scores. Default 0.02.
    pub margin: f64,
    /// `fall_ms`: the time constant with which the speed decided on falls toward a lower
    /// measured speed (display time, each frame at its target time); it rises at once.
    /// Default 300.
    pub fall_ms: f64,
    /// `hand_over`: the time a frame takes from the end of its render to the display, ms:
    /// the band for frame time T ends at T minus it. Default 1.
    pub hand_over_ms: f64,
    /// `warp`: the cost of a warped refresh, ms, when the refreshes between frames show one:
    /// the band for M refreshes ends M − 1 of them earlier. Default 0 (no warps).
    pub warp_ms: f64,
    /// `slack`: the fraction of the frame time kept free under it for timing noise.
    /// Default 0.05.
    pub slack: f64,
    /// `width`: the band's width as a fraction of its frame time. Default 0.2.
    pub width: f64,
    /// The inner predictive controller's options (its `ladder` is the model's).
    pub predictive: PredictiveParams,
}

impl Default for PerceptualParams {
    fn default() -> Self {
        Self {
            model: None,
            hold_ms: 500.0,
            margin: 0.02,
            fall_ms: 300.0,
            hand_over_ms: 1.0,
            warp_ms: 0.0,
            slack: 0.05,
            width: 0.2,
            predictive: PredictiveParams::default(),
        }
    }
}

impl PerceptualParams {
    /// The defaults with the quality model `model` instead of the shipped one.
    pub fn with_model(model: MotionModel) -> Self {
        Self {
            model: Some(model),
            ..Self::default()
        }
    }

    /// Sets one option by name (used by [`crate::from_name`]); `model`, which names a file,
    /// is [`crate::from_name_with`]'s.
    pub fn set(&mut self, key: &str, value: &str) -> Result<(), ConfigError> {
        match key {
            "model" => {
                return Err(ConfigError::BadOption {
                    key: key.to_string(),
                    value: value.to_string(),
                    why: "names a file: set `model` to a parsed MotionModel, or build the \
                          controller with from_name_with"
                        .into(),
                });
            }
            "hold_ms" => self.hold_ms = parse_option(key, value, within(0.0, 1e6))?,
            "margin" => self.margin = parse_option(key, value, within(0.0, 1.0))?,
            "fall_ms" => self.fall_ms = parse_option(key, value, within(0.0, 1e6))?,
            "hand_over" => self.hand_over_ms = parse_option(key, value, within(0.0, 1e3))?,
            "warp" => self.warp_ms = parse_option(key, value, within(0.0, 1e3))?,
            "slack" => self.slack = parse_option(key, value, within(0.0, 0.5))?,
            "width" => self.width = parse_option(key, value, within(0.05, 0.9))?,
            "ladder" => {
                return Err(ConfigError::BadOption {
                    key: key.to_string(),
                    value: value.to_string(),
                    why: "perceptual moves along its model's ladder; give model=PATH for \
                          another one"
                        .into(),
                });
            }
            _ => {
                self.predictive.set(key, value).map_err(|e| match e {
                    ConfigError::UnknownOption { key, .. } => ConfigError::UnknownOption {
                        controller: "perceptual",
                        key,
                        expected: crate::options::expected_keys("perceptual"),
                    },
                    other => other,
                })?;
            }
        }
        Ok(())
    }
}

/// What one frame time promises at the measured speed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Prospect {
    /// The frame time, ms.
    pub frame_ms: f64,
    /// Where on the ladder the predictive controller would settle with this target (below 0:
    /// the cheapest point at lower resolution), or `None` when even its lowest position is
    /// predicted not to fit (or before any frame).
    pub position: Option<f64>,
    /// The model's utility there (higher is better), `None` with no position.
    pub utility: Option<f64>,
}

/// The perceptual controller (see the module documentation).
#[derive(Clone, Debug)]
pub struct Perceptual {
    model: MotionModel,
    /// What its bands are made from besides the model's frame times.
    shaping: Shaping,
    hold_ms: f64,
    margin: f64,
    fall_ms: f64,
    bands: Vec<Band>,
    inner: Predictive,
    /// Index of the target frame time in the model's.
    target: usize,
    /// Display time since the target last changed, ms (each frame at its target time).
    held_ms: f64,
    /// The speed decided on, deg/s: the measured speed, held as it falls (`fall_ms`).
    speed_deg_s: f64,
}

/// How [`Perceptual`] makes the band of each of its model's frame times: the model's display,
/// the band's shape (`slack`, `width`) and the costs it leaves room for (`hand_over`, `warp`).
#[derive(Clone, Copy, Debug)]
struct Shaping {
    display: DisplayConfig,
    shape: BandShape,
    hand_over_ms: f64,
    warp_ms: f64,
}

impl Shaping {
    /// The band of each of `model`'s frame times, or why one has none.
    fn bands(&self, model: &MotionModel) -> Result<Vec<Band>, ConfigError> {
        model
            .frame_times_ms
            .iter()
            .map(|&t| {
                let refreshes = (t / self.display.period_ms()).round().max(1.0) as u32;
                let no_band = |why: String| ConfigError::BadOption {
                    key: "hand_over".into(),
                    value: self.hand_over_ms.to_string(),
                    why: format!(
                        "frame time {t} ms leaves no band after a {} ms hand-over, warped \
                         refreshes of {} ms, a slack of {} and a width of {} of the frame \
                         time: {why}",
                        self.hand_over_ms, self.warp_ms, self.shape.margin, self.shape.width
                    ),
                };
                let (tmin, tmax) = shaped_band(
                    &self.display,
                    refreshes,
                    self.hand_over_ms,
                    self.warp_ms,
                    self.shape,
                )
                .map_err(|e| no_band(e.to_string()))?;
                Band::new(tmin, tmax).map_err(|e| no_band(e.to_string()))
            })
            .collect()
    }
}

impl Perceptual {
    /// A perceptual controller (with the shipped model when `params` has none); errors on a
    /// bad setup or a frame time too short to leave a band after the hand-over and warps.
    pub fn new(setup: Setup, params: PerceptualParams) -> Result<Self, ConfigError> {
        let model = match params.model {
            Some(model) => model,
            None => MotionModel::shipped().map_err(|why| ConfigError::BadOption {
                key: "model".into(),
                value: String::new(),
                why,
            })?,
        }
        .without_dominated_points();
        let display = DisplayConfig::new(model.refresh_hz, SyncMode::Vsync).map_err(|e| {
            ConfigError::BadOption {
                key: "model".into(),
                value: model.refresh_hz.to_string(),
                why: format!("its display: {e}"),
            }
        })?;
        let shaping = Shaping {
            display,
            shape: BandShape {
                margin: params.slack,
                width: params.width,
            },
            hand_over_ms: params.hand_over_ms,
            warp_ms: params.warp_ms,
        };
        let bands = shaping.bands(&model)?;
        let target = bands.len() - 1;
        let inner_params = PredictiveParams {
            ladder: Some(model.ladder.clone()),
            ..params.predictive
        };
        let inner = Predictive::new(
            Setup {
                band: bands[target],
                ..setup
            },
            inner_params,
        )?;
        Ok(Self {
            model,
            shaping,
            hold_ms: params.hold_ms,
            margin: params.margin,
            fall_ms: params.fall_ms,
            bands,
            inner,
            target,
            held_ms: 0.0,
            speed_deg_s: 0.0,
        })
    }

    /// The quality model in use: the one given (or the shipped one) without the ladder
    /// points it scores no better than a cheaper one anywhere
    /// ([`MotionModel::without_dominated_points`]).
    pub fn model(&self) -> &MotionModel {
        &self.model
    }

    /// The target frame time, ms.
    pub fn target_ms(&self) -> f64 {
        self.model.frame_times_ms[self.target]
    }

    /// The band that keeps the target frame time.
    pub fn band(&self) -> Band {
        self.bands[self.target]
    }

    /// The speed the last decision was made at, deg/s (see `fall_ms`).
    pub fn decided_speed_deg_s(&self) -> f64 {
        self.speed_deg_s
    }

    /// The inner predictive controller.
    pub fn predictive(&self) -> &Predictive {
        &self.inner
    }

    /// What every frame time of the model promises at `speed_deg_s`, from the current
    /// view's measurements. Positions below the ladder's cheapest point count only when the
    /// model's stimuli were shown as the frames are ([`Perceptual::trusts_below_ladder`]).
    pub fn prospects(&self, speed_deg_s: f64) -> Vec<Prospect> {
        let below = self.trusts_below_ladder();
        self.bands
            .iter()
            .enumerate()
            .map(|(j, band)| {
                let aim = self.inner.aim_in(*band);
                let position = self
                    .inner
                    .ladder_position_within(aim.target_ms)
                    .filter(|&u| below || u >= 0.0);
                Prospect {
                    frame_ms: self.model.frame_times_ms[j],
                    position,
                    utility: position.map(|u| self.utility_at(speed_deg_s, j, u)),
                }
            })
            .collect()
    }

    /// Whether a frame time reached only below the ladder's cheapest point may be chosen:
    /// when the model's stimuli were shown as the frames are, warped between frames or not
    /// ([`MotionModel::warped`] against a told warp cost above 0). A plain model with warped
    /// refreshes overstates what long frames cost (`docs/temporal.md`: at 32 °/s three
    /// refreshes a frame, 0.091 displayed FLIP over one held, 0.029 warped); trading
    /// resolution below the ladder for shorter frames on its word took `perceptual` with the
    /// history to one refresh at a third of the pixels on meshes, where it had kept two
    /// (`docs/results/scene-suite.md`).
    pub fn trusts_below_ladder(&self) -> bool {
        self.model.warped == (self.shaping.warp_ms > 0.0)
    }

    /// The model's utility at ladder position `u` for frame time `j`: below the cheapest
    /// point, by the rays its lower resolution saves ([`MotionModel::utility_below`]).
    fn utility_at(&self, speed_deg_s: f64, j: usize, u: f64) -> f64 {
        if u >= 0.0 {
            return self.model.utility(speed_deg_s, j, u);
        }
        let ladder = &self.model.ladder;
        let cheapest = f64::from(ladder.points[0].scale);
        let scale = f64::from(self.inner.ladder_quality(ladder, u).scale);
        let cost_ratio = (scale / cheapest).powi(2);
        self.model.utility_below(speed_deg_s, j, cost_ratio)
    }

    /// The frame time to target next, from the prospects: the best, if it beats the current
    /// target by the margin, at once when it is shorter (or the current one cannot be
    /// kept), after the hold when it is longer.
    fn choose(&self, prospects: &[Prospect]) -> usize {
        // Ties go to the longer frame time (the better picture); none feasible: the longest.
        let best = (0..prospects.len())
            .rev()
            .filter_map(|j| prospects[j].utility.map(|u| (j, u)))
            .fold(None, |acc: Option<(usize, f64)>, (j, u)| match acc {
                Some((_, b)) if b >= u => acc,
                _ => Some((j, u)),
            });
        let Some((best, best_utility)) = best else {
            return prospects.len() - 1;
        };
        if best == self.target {
            return self.target;
        }
        match prospects[self.target].utility {
            None => best,
            Some(current) => {
                let margin = self.margin * self.model.spread();
                let better = best_utility > current + margin;
                let shorter = best < self.target;
                if better && (shorter || self.held_ms >= self.hold_ms) {
                    best
                } else {
                    self.target
                }
            }
        }
    }
}

impl Controller for Perceptual {
    fn name(&self) -> &'static str {
        "perceptual"
    }

    fn quality(&self) -> Quality {
        self.inner.quality()
    }

    fn observe(&mut self, report: &FrameReport) -> Result<Quality, ReportError> {
        let speed = report.speed_deg_s;
        if !(speed.is_finite() && speed >= 0.0) {
            return Err(ReportError::BadSpeed(speed));
        }
        self.inner.observe(report)?;
        let elapsed = self.target_ms();
        self.held_ms += elapsed;
        let kept = if self.fall_ms > 0.0 {
            self.speed_deg_s * (-elapsed / self.fall_ms).exp()
        } else {
            0.0
        };
        self.speed_deg_s = speed.max(kept);
        let next = self.choose(&self.prospects(self.speed_deg_s));
        if next != self.target {
            self.target = next;
            self.held_ms = 0.0;
            self.inner.retarget(self.bands[next]);
        }
        Ok(self.inner.quality())
    }

    fn reset(&mut self) {
        self.inner.reset();
        self.target = self.bands.len() - 1;
        self.held_ms = 0.0;
        self.speed_deg_s = 0.0;
        self.inner.retarget(self.bands[self.target]);
    }

    fn target_frame_ms(&self) -> Option<f64> {
        Some(self.target_ms())
    }

    /// The inner `predictive`'s budget, for the band of the frame time chosen.
    fn frame_budget(&self) -> Option<FrameBudget> {
        self.inner.frame_budget()
    }

    /// The inner `predictive`'s decision (a new target frame time shows as a new band).
    fn decision(&self) -> Option<&Decision> {
        self.inner.decision()
    }

    /// Its bands are its model's frame times': a band from outside changes none of them.
    fn set_band(&mut self, _band: Band) {}

    /// Makes its bands again with the costs told, keeping its target frame time, its hold
    /// and the inner controller's cost model (which moves to the target's new band).
    fn set_display_costs(&mut self, costs: DisplayCosts) -> Result<(), ConfigError> {
        let shaping = Shaping {
            hand_over_ms: costs.hand_over_ms.unwrap_or(self.shaping.hand_over_ms),
            warp_ms: costs.warp_ms.unwrap_or(self.shaping.warp_ms),
            ..self.shaping
        };
        for (key, ms) in [
            ("hand_over", shaping.hand_over_ms),
            ("warp", shaping.warp_ms),
        ] {
            within(0.0, 1e3)(&ms).map_err(|why| ConfigError::BadOption {
                key: key.into(),
                value: ms.to_string(),
                why,
            })?;
        }
        self.bands = shaping.bands(&self.model)?;
        self.shaping = shaping;
        self.inner.retarget(self.bands[self.target]);
        Ok(())
    }
}
