//! The controller of the live view, switched and retuned while it runs: a new controller,
//! band or bounds takes effect at the next frame and starts from the quality in use, so a
//! change never jumps the image to the starting quality. A new band keeps the controller
//! and what it has learned (its cost model); a new controller or new bounds build one.

use anyhow::{Result, bail};
use steadyray_control::ControllerSpec;
use steadyray_control::{
    Band, Bounds, CONTROLLER_NAMES, Controller, DisplayCosts, FrameBudget, FrameReport, Quality,
    ReportError, Setup, from_name_with,
};
use steadyray_experiment::files::DiskFiles;

/// The controller in use and what it was built from.
#[derive(Debug)]
pub struct LiveControl {
    /// The controller named on the command line and its options; the options apply to that
    /// controller only (others run with their defaults).
    initial: (String, String),
    band: Band,
    bounds: Bounds,
    controller: Box<dyn Controller>,
    /// What handing a frame to the window and warping a refresh cost, once measured.
    display_costs: Option<MeasuredCosts>,
}

/// The window's measured costs around a frame (`--band refresh[:M]`, `--warp`): a
/// `perceptual` controller is told them, as `bench` tells it, so that its bands leave room
/// for them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeasuredCosts {
    pub hand_over_ms: f64,
    /// 0 where the window shows no warped refreshes.
    pub warp_ms: f64,
}

impl LiveControl {
    /// Builds controller `name` with `options` over `band` and `bounds`, starting at `start`.
    pub fn new(
        name: &str,
        options: &str,
        band: Band,
        bounds: Bounds,
        start: Quality,
    ) -> Result<Self> {
        let controller =
            from_name_with(name, Setup::new(band, bounds, start)?, options, &DiskFiles)?;
        Ok(Self {
            initial: (name.to_string(), options.to_string()),
            band,
            bounds,
            controller,
            display_costs: None,
        })
    }

    /// Tells the controller (`perceptual`, the one that uses them) the window's measured
    /// costs, unless its options give them, keeping what it has learned
    /// (`Controller::set_display_costs`); a controller built later is built with them. On an
    /// error nothing changes.
    pub fn set_display_costs(&mut self, costs: MeasuredCosts) -> Result<()> {
        let given = self.given(self.name());
        let told = DisplayCosts {
            hand_over_ms: given.lacks("hand_over").then_some(costs.hand_over_ms),
            warp_ms: given.lacks("warp").then_some(costs.warp_ms),
        };
        self.controller.set_display_costs(told)?;
        self.display_costs = Some(costs);
        Ok(())
    }

    /// The controller's name.
    pub fn name(&self) -> &'static str {
        self.controller.name()
    }

    pub fn band(&self) -> Band {
        self.band
    }

    pub fn bounds(&self) -> Bounds {
        self.bounds
    }

    /// The frame time the controller has chosen (`perceptual`), ms.
    pub fn target_frame_ms(&self) -> Option<f64> {
        self.controller.target_frame_ms()
    }

    /// The time budget the controller hands the next frame, if it hands any
    /// (`predictive:budget=true`).
    pub fn frame_budget(&self) -> Option<FrameBudget> {
        self.controller.frame_budget()
    }

    /// The quality of the next frame.
    pub fn quality(&self) -> Quality {
        self.controller.quality()
    }

    /// Shows the controller the frame just rendered.
    pub fn observe(&mut self, report: &FrameReport) -> Result<Quality, ReportError> {
        self.controller.observe(report)
    }

    /// Switches to controller `name` (one of [`CONTROLLER_NAMES`]), starting at the current
    /// quality.
    pub fn set_controller(&mut self, name: &str) -> Result<()> {
        if !CONTROLLER_NAMES.contains(&name) {
            bail!(
                "unknown controller {name:?} (expected one of: {})",
                CONTROLLER_NAMES.join(", ")
            );
        }
        self.rebuild(name, self.band, self.bounds)
    }

    /// Uses the band [`tmin_ms`, `tmax_ms`] from the next frame on, with the same controller
    /// and what it has learned (`Controller::set_band`).
    pub fn set_band(&mut self, tmin_ms: f64, tmax_ms: f64) -> Result<()> {
        let band = Band::new(tmin_ms, tmax_ms)?;
        self.controller.set_band(band);
        self.band = band;
        Ok(())
    }

    /// Uses `bounds` from the next frame on; the quality in use is clamped into them.
    pub fn set_bounds(&mut self, bounds: Bounds) -> Result<()> {
        bounds.validate()?;
        self.rebuild(self.name(), self.band, bounds)
    }

    /// The options controller `name` is built with: those given for it on the command line,
    /// and for `perceptual` the measured display costs its options do not give.
    fn options_for(&self, name: &str) -> String {
        let mut spec = self.given(name);
        if let Some(costs) = self.display_costs {
            spec.tell_measured("hand_over", costs.hand_over_ms);
            spec.tell_measured("warp", costs.warp_ms);
        }
        spec.options
    }

    /// Controller `name` with the options the command line gave for it.
    fn given(&self, name: &str) -> ControllerSpec {
        ControllerSpec {
            name: name.to_string(),
            options: if name == self.initial.0 {
                self.initial.1.clone()
            } else {
                String::new()
            },
        }
    }

    /// Replaces the controller; on an error nothing changes.
    fn rebuild(&mut self, name: &str, band: Band, bounds: Bounds) -> Result<()> {
        let start = bounds.clamp(self.quality());
        let options = self.options_for(name);
        self.controller =
            from_name_with(name, Setup::new(band, bounds, start)?, &options, &DiskFiles)?;
        self.band = band;
        self.bounds = bounds;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn control(name: &str, options: &str) -> LiveControl {
        let bounds = Bounds::default();
        let start = Quality::new(1.0, 16, 1.0);
        LiveControl::new(name, options, Band::PAPER, bounds, start).unwrap()
    }

    fn report(tp_ms: f64, q: Quality) -> FrameReport {
        FrameReport {
            tp_ms,
            rays_per_depth: vec![10_000, 5_000],
            rays_stopped: None,
            shadow_rays: 8_000,
            pixels: 10_000,
            quality: q,
            speed_deg_s: 0.0,
            first_sample: None,
        }
    }

    #[test]
    fn switching_keeps_the_quality_in_use() {
        let mut c = control("step", "");
        let q0 = c.quality();
        let q1 = c.observe(&report(40.0, q0)).unwrap();
        assert!(q1.level() < q0.level(), "an overload cuts: {q0} -> {q1}");
        c.set_controller("fixed").unwrap();
        assert_eq!((c.name(), c.quality()), ("fixed", q1));
        c.observe(&report(40.0, q1)).unwrap();
        assert_eq!(c.quality(), q1, "fixed does not move");
    }

    #[test]
    fn options_stay_with_the_controller_they_were_given_for() {
        let mut c = control("step", "knob=spp");
        c.set_controller("hysteresis").unwrap();
        c.set_controller("step").unwrap();
        assert_eq!(c.name(), "step");
        assert!(
            LiveControl::new(
                "fixed",
                "knob=spp",
                Band::PAPER,
                Bounds::default(),
                Quality::new(1.0, 0, 1.0)
            )
            .is_err()
        );
    }

    #[test]
    fn bad_changes_are_refused_and_change_nothing() {
        let mut c = control("predictive", "");
        assert!(c.set_controller("fastest").is_err());
        assert!(c.set_band(20.0, 15.0).is_err());
        let bounds = Bounds {
            spp_min: 0.5,
            ..Bounds::default()
        };
        assert!(c.set_bounds(bounds).is_err());
        assert_eq!(c.name(), "predictive");
        assert_eq!(c.band(), Band::PAPER);
        assert_eq!(c.bounds(), Bounds::default());
    }

    #[test]
    fn new_bounds_and_band_apply_at_once() {
        let mut c = control("hysteresis", "");
        let bounds = Bounds {
            depth_max: 4,
            ..Bounds::default()
        };
        c.set_bounds(bounds).unwrap();
        assert_eq!(c.quality().depth, 4, "clamped into the new bounds");
        c.set_band(8.0, 12.0).unwrap();
        assert_eq!(c.band(), Band::new(8.0, 12.0).unwrap());
        assert_eq!(c.quality().depth, 4);
    }

    /// A band measured from the display (or edited in the HUD) keeps the controller and its
    /// fitted cost model: `predictive` plans the next frame for the new band at once.
    #[test]
    fn a_new_band_keeps_what_the_controller_learned() {
        let mut c = control("predictive", "");
        // Frames whose rays, and time, follow the quality: 1 ms + 1 µs a ray.
        let frame = |q: Quality| {
            let eye = 1e5 * f64::from(q.spp * q.scale * q.scale);
            let rays: Vec<u64> = (0..=q.depth)
                .map(|k| (eye / f64::from(k + 1)) as u64)
                .collect();
            FrameReport {
                tp_ms: 1.0 + rays.iter().sum::<u64>() as f64 * 1e-6,
                rays_per_depth: rays,
                shadow_rays: 0,
                rays_stopped: None,
                pixels: 100_000,
                quality: q,
                speed_deg_s: 0.0,
                first_sample: None,
            }
        };
        for _ in 0..30 {
            let r = frame(c.quality());
            c.observe(&r).unwrap();
        }
        let settled = c.quality();
        c.set_band(30.0, 40.0).unwrap();
        let next = c.quality();
        assert!(next.level() > settled.level(), "{settled} -> {next}");
        assert!(c.band().contains(frame(next).tp_ms), "{next}");
    }

    #[test]
    fn perceptual_is_told_the_measured_costs_its_options_do_not_give() {
        let mut c = control("fixed", "");
        let costs = MeasuredCosts {
            hand_over_ms: 1.5,
            warp_ms: 6.25,
        };
        c.set_display_costs(costs).unwrap();
        assert_eq!(c.options_for("fixed"), "", "only perceptual takes them");
        c.initial = ("perceptual".into(), "model=m.json hand_over=2".into());
        assert_eq!(
            c.options_for("perceptual"),
            "model=m.json hand_over=2 warp=6.250"
        );
        c.initial.1 = "model=m.json".into();
        assert_eq!(
            c.options_for("perceptual"),
            "model=m.json hand_over=1.500 warp=6.250"
        );
    }
}
