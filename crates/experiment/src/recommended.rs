//! The recommended configuration of the live display per backend (docs/results/viewer.md,
//! "Recommended configuration"): what `view` starts with and what `bench --display` runs.
//! Stated once here so the viewer's default, the bench preset and the help cannot drift.

use crate::bench::BenchConfig;
use crate::config::{BackendChoice, ClockChoice, TemporalChoice};
use steadyray_display::RefreshBand;
use steadyray_render_gpu::list_adapters;

/// The band, temporal mode and warps measured best on one backend.
///
/// On the CPU renderer, decided on the scene suite (docs/results/scene-suite.md): a frame
/// every two refreshes with the temporal history and the refresh between shown warped has
/// the best mean rank of the suite's methods over its six scenes (by displayed FLIP; on the
/// corridor it also scored the highest JOD, docs/results/viewer.md). On a GPU, where frames
/// carry many samples, one refresh without the history looked as good on the corridor; the
/// suite has not run on a GPU.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Recommended {
    /// The band: a frame every this many refreshes (`--band refresh:M`).
    pub refreshes_per_frame: u32,
    /// Whether frames accumulate into the temporal history (`--temporal on`).
    pub temporal: bool,
    /// Whether the refreshes between frames show the last frame warped (`--warp`).
    pub warp: bool,
}

impl Recommended {
    /// The CPU renderer's: `--band refresh:2 --temporal on --warp`.
    pub const CPU: Recommended = Recommended {
        refreshes_per_frame: 2,
        temporal: true,
        warp: true,
    };
    /// A GPU's: `--band refresh --temporal off`.
    pub const GPU: Recommended = Recommended {
        refreshes_per_frame: 1,
        temporal: false,
        warp: false,
    };

    /// The recommendation for a renderer on a GPU (`gpu`) or on the CPU.
    pub fn for_backend(gpu: bool) -> Self {
        if gpu { Self::GPU } else { Self::CPU }
    }

    /// The recommendation for the renderer `choice` will pick: `auto` picks a GPU where a
    /// hardware adapter is present (as [`crate::backend::create_renderer`] does).
    pub fn for_choice(choice: BackendChoice) -> Self {
        Self::for_backend(match choice {
            BackendChoice::Cpu => false,
            BackendChoice::Gpu => true,
            BackendChoice::Auto => list_adapters().iter().any(|a| !a.is_software),
        })
    }

    /// The flags this recommendation stands for, as `bench` and `view` spell them.
    pub fn flags(self) -> String {
        let band = match self.refreshes_per_frame {
            1 => "--band refresh".to_string(),
            m => format!("--band refresh:{m}"),
        };
        let temporal = if self.temporal { "on" } else { "off" };
        let warp = if self.warp { " --warp" } else { "" };
        format!("{band} --temporal {temporal}{warp}")
    }

    /// `bench --display`: the display experiment (`--clock real`) in this configuration.
    /// On the simulated renderer, which keeps no history, the band alone.
    pub fn apply_to_bench(self, config: &mut BenchConfig) {
        let with_history = self.temporal && !config.simulate;
        config.clock = ClockChoice::Real;
        config.band = Some(RefreshBand {
            multiple: if config.simulate {
                Self::GPU.refreshes_per_frame
            } else {
                self.refreshes_per_frame
            },
        });
        config.temporal = if with_history {
            TemporalChoice::On
        } else {
            TemporalChoice::Off
        };
        config.warp = self.warp && with_history;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_flags_spell_each_backends_recommendation() {
        assert_eq!(
            Recommended::CPU.flags(),
            "--band refresh:2 --temporal on --warp"
        );
        assert_eq!(Recommended::GPU.flags(), "--band refresh --temporal off");
        assert_eq!(
            Recommended::for_choice(BackendChoice::Cpu),
            Recommended::CPU
        );
        assert_eq!(
            Recommended::for_choice(BackendChoice::Gpu),
            Recommended::GPU
        );
    }

    #[test]
    fn the_bench_preset_runs_the_display_experiment_in_it() {
        let mut config = BenchConfig::default();
        Recommended::CPU.apply_to_bench(&mut config);
        assert_eq!(config.clock, ClockChoice::Real);
        assert_eq!(config.band, Some(RefreshBand { multiple: 2 }));
        assert_eq!(config.temporal, TemporalChoice::On);
        assert!(config.warp);
        let mut simulated = BenchConfig {
            simulate: true,
            ..BenchConfig::default()
        };
        Recommended::CPU.apply_to_bench(&mut simulated);
        assert_eq!(simulated.band, Some(RefreshBand { multiple: 1 }));
        assert_eq!(simulated.temporal, TemporalChoice::Off);
        assert!(!simulated.warp);
    }
}
