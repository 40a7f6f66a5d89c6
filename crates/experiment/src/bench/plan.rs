//! The bench's first phase: its configuration checked before anything renders (the bounds
//! and start quality, the clock and display, the controllers).

use super::{BenchConfig, BestLookingFixed};
use crate::config::{ClockChoice, TemporalChoice};
use crate::files::DiskFiles;
use anyhow::{Context, Result, bail};
use steadyray_control::{
    Band, Bounds, Controller, ControllerSpec, Quality, Setup, parse_controllers,
};
use steadyray_display::{DisplayConfig, SyncMode};
use steadyray_render::sample_stream::check_reference_spp;

/// A bench's configuration, checked.
pub struct Plan {
    /// The quality knobs' bounds.
    pub bounds: Bounds,
    /// Every controller's start, and the paper's fixed baseline.
    pub start: Quality,
    /// The display under the real clock; `None` under the frame clock.
    pub display: Option<DisplayConfig>,
    /// The controllers, one per `--controllers` entry, in order (none with
    /// `--only-best-looking-fixed`).
    pub specs: Vec<ControllerSpec>,
}

impl Plan {
    /// Checks `config`: every mistake is an error before anything renders (a band aligned
    /// with the display is only known once the hand-over is measured, so the controllers are
    /// tried in the configuration's band).
    pub fn check(config: &BenchConfig) -> Result<Self> {
        let bounds = config.bounds;
        bounds.validate()?;
        let start = Quality {
            spp: bounds.spp_min,
            depth: config.fixed_depth.unwrap_or(bounds.depth_max),
            scale: bounds.scale_max,
        };
        if config.frames == 0 {
            bail!("--frames must be at least 1");
        }
        if let Some(spp) = config.reference_spp {
            check_reference_spp(spp)?;
        }
        check_best_looking(config)?;
        let display = real_display(config)?;
        if config.simulate && config.temporal != TemporalChoice::Off {
            bail!("--temporal needs a renderer (not --simulate)");
        }
        let plan = Self {
            bounds,
            start,
            display,
            specs: match config.best_looking_fixed {
                BestLookingFixed::Only => Vec::new(),
                _ => parse_controllers(&config.controllers)?,
            },
        };
        plan.build(Band::new(config.tmin, config.tmax)?, &plan.specs)?;
        Ok(plan)
    }

    /// The set-up of runs in `band` and one controller per spec of `specs`.
    pub fn build(
        &self,
        band: Band,
        specs: &[ControllerSpec],
    ) -> Result<(Setup, Vec<Box<dyn Controller>>)> {
        let setup = Setup::new(band, self.bounds, self.start)
            .context("--fixed-depth is outside the R bounds")?;
        let controllers = specs
            .iter()
            .map(|s| Ok(s.build(setup, &DiskFiles)?))
            .collect::<Result<Vec<_>>>()?;
        Ok((setup, controllers))
    }
}

/// Refuses `--only-best-looking-fixed` where the bench does not measure the displayed
/// quality that chooses it.
fn check_best_looking(config: &BenchConfig) -> Result<()> {
    let measured = config.clock == ClockChoice::Real && config.quality;
    if config.best_looking_fixed == BestLookingFixed::Only && !measured {
        bail!(
            "--only-best-looking-fixed chooses the fixed quality with the lowest displayed \
             FLIP: it needs --clock real --quality"
        );
    }
    Ok(())
}

/// Checks the clock options: the display's under `--clock real`, none of them under the
/// frame clock, and `--record` only under the frame clock.
fn real_display(config: &BenchConfig) -> Result<Option<DisplayConfig>> {
    match config.clock {
        ClockChoice::Frames => {
            if config.duration.is_some()
                || config.display.is_given()
                || config.video.is_some()
                || config.references.is_some()
                || config.warp
            {
                bail!(
                    "--duration, --refresh, --vsync, --vrr, --video, --references and --warp \
                     need --clock real"
                );
            }
            Ok(None)
        }
        ClockChoice::Real => {
            if config.record.is_some() {
                bail!("--record keeps frames of the frame clock; with --clock real use --video");
            }
            if config.simulate && (config.quality || config.video.is_some()) {
                bail!(
                    "--quality and --video need a renderer that produces images (not --simulate)"
                );
            }
            if config.references.is_some() && !config.quality && config.video.is_none() {
                bail!("--references keeps the references of --quality or --video: give either");
            }
            let display = config.display.config()?;
            if config.warp {
                if config.temporal == TemporalChoice::Off {
                    bail!("--warp shows a temporal history again: it needs --temporal on or both");
                }
                if display.sync != SyncMode::Vsync {
                    bail!("--warp fills the refreshes of a display with vsync on (--vsync on)");
                }
            }
            Ok(Some(display))
        }
    }
}
