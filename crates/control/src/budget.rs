//! Frame budgets from a controller's side: the budget that keeps frames in a band
//! ([`for_band`]) and how much of it a planned frame's first sample may take
//! ([`BASE_SHARE`]). The budget itself and the schedule a renderer follows are the crate
//! `steadyray-budget`, re-exported here.

pub use steadyray_budget::*;

use crate::band::Band;

/// The share of the band, below its top, kept free by [`for_band`] for what a frame does
/// after its last unit (averaging the samples, the timer's reading) and for a unit that
/// runs slower than the one before it.
pub const STOP_MARGIN: f64 = 0.1;

/// The most of [`FrameBudget::stop_by_ms`] a controller handing out budgets plans a frame's
/// first sample of every pixel to take: the part of the frame no budget can cut. A timing
/// spike of up to 1/0.85 = 1.18 times (beyond the shared 2-core VM's 95th percentile, frame
/// against its neighbours) during it still ends the frame in time. At 0.7 (spikes to 1.43
/// times) the corridor kept 99.4 % of frames in the band but at a lower resolution:
/// displayed FLIP 0.0075 against 0.0067 at 0.85 (98.9 %), `predictive` alone 0.0063.
pub const BASE_SHARE: f64 = 0.85;

/// The time a frame in `band` must stop adding samples by: [`STOP_MARGIN`] of the band
/// below its top.
pub fn stop_by_ms(band: Band) -> f64 {
    band.tmax_ms() - STOP_MARGIN * band.width_ms()
}

/// The budget that keeps frames in `band` aiming at `target_ms`: filled up to the target,
/// stopped [`STOP_MARGIN`] of the band below its top, filled up to `max_spp` (at least 1).
/// `target_ms` is clamped into the band's stopping range.
pub fn for_band(band: Band, target_ms: f64, max_spp: f32) -> FrameBudget {
    let stop_by = stop_by_ms(band);
    FrameBudget::new(
        target_ms.clamp(band.tmin_ms(), stop_by),
        stop_by,
        max_spp.max(1.0),
    )
    .expect("a band's times are finite and positive")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_band_budget_fills_to_the_target_and_stops_below_the_top() {
        let band = Band::new(15.0, 20.0).unwrap();
        let b = for_band(band, 17.5, 8.0);
        assert_eq!(
            (b.fill_until_ms, b.stop_by_ms, b.max_spp),
            (17.5, 19.5, 8.0)
        );
        // A target past the stopping time is held to it.
        assert_eq!(for_band(band, 19.9, 8.0).fill_until_ms, 19.5);
    }
}
