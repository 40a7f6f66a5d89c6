//! The workload and how it changes: a schedule of load levels over the frames, and the
//! calibration that turns "load 1" into a number of fractal steps per pixel on this GPU.

/// The load levels the schedule cycles through, each held for a phase: at full resolution,
/// level 1 costs the band's centre, so a fixed scale of 1 fits only the first phase while a
/// controller must find about 0.71, 0.53 and 0.85 of the resolution for the others.
pub const LEVELS: [f64; 4] = [1.0, 2.0, 3.5, 1.4];

/// Which load level a frame runs at: the levels of [`LEVELS`] in turn, each for
/// `phase_frames` frames, then again from the first.
#[derive(Clone, Copy, Debug)]
pub struct Schedule {
    /// Frames each level is held.
    pub phase_frames: u64,
    /// Fractal steps per pixel at load 1 (from [`base_iterations`]).
    pub base_iterations: f64,
}

impl Schedule {
    /// The load level of frame `frame`.
    pub fn level(&self, frame: u64) -> f64 {
        let phase = (frame / self.phase_frames.max(1)) as usize;
        LEVELS[phase % LEVELS.len()]
    }

    /// The fractal steps per pixel of frame `frame`.
    pub fn iterations(&self, frame: u64) -> u32 {
        iterations_for(self.base_iterations * self.level(frame))
    }
}

/// The most fractal steps a pixel may take (a guard against a calibration gone wild).
pub const MAX_ITERATIONS: u32 = 1 << 22;

/// A step count for a fractional load, at least 1.
pub fn iterations_for(steps: f64) -> u32 {
    steps.round().clamp(1.0, f64::from(MAX_ITERATIONS)) as u32
}

/// What one calibration frame measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Fractal steps per pixel.
    pub iterations: u32,
    /// Pixels drawn by the heavy pass.
    pub pixels: u64,
    /// Its frame time, ms.
    pub ms: f64,
}

/// Fractal steps per pixel at which a full-resolution frame of `pixels` pixels costs
/// `target_ms`, from `overhead_ms` (a frame without steps: the upscale and the passes'
/// fixed cost) and `heavy` (frames with steps), fitting ms = overhead + k · pixels · steps.
/// An error says why no fit exists (no heavy frame slower than the overhead, or a target
/// the overhead alone exceeds).
pub fn base_iterations(
    overhead_ms: f64,
    heavy: &[Sample],
    pixels: u64,
    target_ms: f64,
) -> Result<f64, String> {
    let work: f64 = heavy
        .iter()
        .map(|s| s.pixels as f64 * f64::from(s.iterations))
        .sum();
    let extra: f64 = heavy.iter().map(|s| s.ms - overhead_ms).sum();
    if work <= 0.0 || extra <= 0.0 {
        return Err(format!(
            "the heavy frames took no longer than the overhead ({overhead_ms:.3} ms): \
             nothing to calibrate the load on"
        ));
    }
    if target_ms <= overhead_ms {
        return Err(format!(
            "the frame's fixed cost ({overhead_ms:.2} ms) already exceeds the band's centre \
             ({target_ms:.2} ms): try a smaller window or a lower refresh rate"
        ));
    }
    let ms_per_step = extra / work;
    Ok((target_ms - overhead_ms) / (ms_per_step * pixels as f64))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_cycle_by_phase() {
        let s = Schedule {
            phase_frames: 10,
            base_iterations: 100.0,
        };
        assert_eq!(s.level(0), 1.0);
        assert_eq!(s.level(9), 1.0);
        assert_eq!(s.level(10), 2.0);
        assert_eq!(s.level(35), 1.4);
        assert_eq!(s.level(40), 1.0);
        assert_eq!(s.iterations(25), 350);
    }

    #[test]
    fn calibration_inverts_a_linear_cost() {
        // 0.5 ms fixed, 1e-6 ms per pixel-step.
        let cost =
            |pixels: u64, iterations: u32| 0.5 + 1e-6 * pixels as f64 * f64::from(iterations);
        let heavy: Vec<Sample> = [64, 256]
            .iter()
            .map(|&iterations| Sample {
                iterations,
                pixels: 10_000,
                ms: cost(10_000, iterations),
            })
            .collect();
        let base = base_iterations(0.5, &heavy, 40_000, 10.0).unwrap();
        // (10 - 0.5) ms / (1e-6 ms × 40,000 pixels) = 237.5 steps.
        assert!((base - 237.5).abs() < 1e-9, "{base}");
    }

    #[test]
    fn calibration_refuses_what_it_cannot_fit() {
        let flat = [Sample {
            iterations: 64,
            pixels: 100,
            ms: 1.0,
        }];
        assert!(base_iterations(1.0, &flat, 100, 10.0).is_err());
        let heavy = [Sample {
            iterations: 64,
            pixels: 100,
            ms: 20.0,
        }];
        assert!(
            base_iterations(12.0, &heavy, 100, 10.0)
                .unwrap_err()
                .contains("fixed cost")
        );
    }

    #[test]
    fn iterations_stay_in_range() {
        assert_eq!(iterations_for(0.2), 1);
        assert_eq!(iterations_for(f64::MAX), MAX_ITERATIONS);
    }
}
