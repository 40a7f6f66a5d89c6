//! `bench --clock real`: each controller runs for a span of display time on the display model
//! (`steadyray_display`), rendering each frame's world at its predicted display time. Display
//! time advances by the measured Tp, hand-over and (`--warp`) warp costs alone, so whatever
//! the bench does between frames (reading pictures back, keeping them) changes no figure.

use super::record::{ControllerRun, FrameRow};
use super::screen::{DisplayRun, Warps};
use super::source::{FrameSource, PathPoint};
use anyhow::{Context, Result};
use indicatif::ProgressBar;
use std::collections::BTreeMap;
use std::time::Instant;
use steadyray_control::{Band, Bounds, Controller, FrameRecord, summarize};
use steadyray_display::model::{TIME_EPS_MS, refresh_at_or_after};
use steadyray_display::{DisplayConfig, DisplayFigures, FrameSlot, FrameTimes, RealClock};
use steadyray_quality::Rgb8Image;

/// What every real-clock run follows.
#[derive(Clone, Copy, Debug)]
pub struct RealSweep {
    /// The display model.
    pub display: DisplayConfig,
    /// Display time per run, s.
    pub duration_s: f64,
    /// Frames rendered (and shown to the controller) before the run, one refresh apart on
    /// the path's time up to its start (t = −warmup·P, ..., −P: a looping path's lead-in),
    /// so the controller's first measurements, and a temporal history, are of a moving
    /// camera as in the run; the last of them is on screen until the run's first frame
    /// replaces it.
    pub warmup: u32,
    /// The frame-time band.
    pub band: Band,
    /// The quality knobs' bounds.
    pub bounds: Bounds,
    /// Whether a refresh whose frame on screen rendered the world of another time shows
    /// that frame warped to the refresh's camera (`bench --warp`, `Renderer::present_warped`):
    /// a refresh without a new frame, whose warp is made while the next frame renders and
    /// delays that frame's completion, never past the refresh it makes without warps (the
    /// controller sees the frame's own Tp); and a frame's first refresh when the frame came
    /// earlier or later than predicted, whose warp is made between the frame's completion
    /// and its refresh, when it fits there.
    pub warp: bool,
}

/// The most warps of the frame on screen made before the next frame renders. The bench works
/// in turn, so it cannot know yet how many refreshes that frame will leave without a new
/// frame: it makes those the frame would leave if it took as long as the last one, and one
/// more (`warps_to_make`); a frame slower than that leaves the refreshes after them
/// unwarped, counted as missed.
pub const WARPS_AHEAD: usize = 4;

/// Which samples of the screen (at the display's refresh rate: sample i at i·P) a run keeps
/// the pictures of, for a video or the displayed quality.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Keep {
    /// No pictures.
    Nothing,
    /// One sample in K, its place in each run of K moving on by one from run to run: sample
    /// i where i mod K = ⌊i / K⌋ mod K (K = 2: 0, 3, 4, 7, 8, ...; `Every(1)`: all of them).
    /// A fixed place (0, K, 2K, ...) aliases with frames shown for a number of refreshes
    /// sharing a factor with K: at K = 2, frames shown for two refreshes each (30 frames a
    /// second at 60 Hz) were all seen at their first refresh, or all at their second, and
    /// the mean screen age, with it displayed FLIP, hung on which.
    Every(u32),
}

impl Keep {
    /// Whether sample `i` is kept.
    pub fn wants(self, i: usize) -> bool {
        match self {
            Keep::Nothing => false,
            Keep::Every(k) => {
                let k = k.max(1) as usize;
                i % k == (i / k) % k
            }
        }
    }

    /// Whether a kept sample falls in [`from_ms`, `to_ms`) and before `end_ms`, samples being
    /// every `period_ms`: whether a frame on screen over that span must be kept.
    fn any_in(self, from_ms: f64, to_ms: f64, period_ms: f64, end_ms: f64) -> bool {
        if self == Keep::Nothing {
            return false;
        }
        let last_ms = to_ms.min(end_ms) - TIME_EPS_MS;
        (refresh_at_or_after(from_ms, period_ms)..)
            .take_while(|&i| (i as f64 * period_ms) < last_ms)
            .any(|i| self.wants(i as usize))
    }
}

/// A warp made ahead of the next frame: the frame on screen warped to refresh `refresh`.
struct Ahead {
    refresh: usize,
    ms: f64,
    picture: Option<Rgb8Image>,
}

/// How many warps to make ahead of a frame starting at `start_ms`, the first refresh it may
/// leave without a new frame being `first`: those before `start_ms + last_busy_ms` (the last
/// frame's render and hand-over), and one more for a frame slower than the last, at most
/// [`WARPS_AHEAD`]. A warp made and not shown is work for nothing that leaves the renderer
/// idle meanwhile (on the CPU a warp at 640 × 360 costs about 7 ms; a GPU's clocks fall when
/// it idles): with four made before every frame, frames at one refresh (which leave none)
/// took 36 % of a CPU run's wall time.
fn warps_to_make(first: usize, start_ms: f64, last_busy_ms: f64, period_ms: f64) -> usize {
    let complete = start_ms + last_busy_ms;
    let held = (first..)
        .take_while(|&i| (i as f64 * period_ms) < complete - TIME_EPS_MS)
        .take(WARPS_AHEAD)
        .count();
    (held + 1).min(WARPS_AHEAD)
}

/// The warps of the frame on screen to the `count` refreshes from `first` (before the run's
/// end `end_ms`), each at its refresh's world time, with the pictures `keep` asks for.
fn warps_ahead(
    source: &mut dyn FrameSource,
    (first, count): (usize, usize),
    period_ms: f64,
    end_ms: f64,
    keep: Keep,
) -> Result<Vec<Ahead>> {
    (first..first + count)
        .map(|refresh| (refresh, refresh as f64 * period_ms))
        .take_while(|&(_, time_ms)| time_ms < end_ms - TIME_EPS_MS)
        .map(|(refresh, time_ms)| {
            let handed = source
                .warp(time_ms / 1000.0, keep.wants(refresh))
                .with_context(|| format!("warp to refresh {refresh}"))?;
            Ok(Ahead {
                refresh,
                ms: handed.ms,
                picture: handed.image,
            })
        })
        .collect()
}

/// What a frame starting at `start_ms` and busy for `busy_ms` (render and hand-over) does
/// with the warps `ahead` (made for the refreshes from the first one it may leave without a
/// new frame): how many it uses, and how many refreshes it leaves without a new frame
/// (those before it completes, up to the run's end `end_ms`). The warps are made in the
/// order of their refreshes, each delaying the frame, and only as many as still let it
/// make the refresh it makes without them: a warp never costs a frame a refresh, so warps
/// slower than a refresh do not cascade into ever later frames.
fn warps_used(
    ahead: &[Ahead],
    start_ms: f64,
    busy_ms: f64,
    period_ms: f64,
    end_ms: f64,
) -> (usize, usize) {
    let Some(first) = ahead.first() else {
        return (0, 0);
    };
    let complete = start_ms + busy_ms;
    let held = (first.refresh..)
        .map(|i| i as f64 * period_ms)
        .take_while(|&t| t < complete - TIME_EPS_MS && t < end_ms - TIME_EPS_MS)
        .count();
    let shown_ms = refresh_at_or_after(complete, period_ms) as f64 * period_ms;
    let mut busy = complete;
    let used = ahead[..held.min(ahead.len())]
        .iter()
        .take_while(|w| {
            busy += w.ms;
            busy <= shown_ms + TIME_EPS_MS
        })
        .count();
    (used, held)
}

/// A frame shown at another refresh than the one it rendered the world of (its render or
/// hand-over took longer or shorter than predicted) is warped to its refresh's time, if the
/// warp fits between the frame's completion and that refresh (the renderer waits there for
/// the screen to release a buffer); a warp that does not fit is missed.
fn warp_first_showing(
    source: &mut dyn FrameSource,
    slot: &FrameSlot,
    times: &FrameTimes,
    period_ms: f64,
    end_ms: f64,
    keep: Keep,
    warps: &mut Warps,
) -> Result<()> {
    let (shown_ms, rendered_ms) = (times.visible_ms, slot.show_ms);
    if (shown_ms - rendered_ms).abs() <= TIME_EPS_MS || shown_ms >= end_ms - TIME_EPS_MS {
        return Ok(());
    }
    let refresh = refresh_at_or_after(shown_ms, period_ms) as usize;
    let handed = source
        .warp(shown_ms / 1000.0, keep.wants(refresh))
        .with_context(|| format!("warp to refresh {refresh}"))?;
    if times.complete_ms() + handed.ms > shown_ms + TIME_EPS_MS {
        warps.missed += 1;
    } else {
        warps.record(refresh, handed.ms, handed.image);
    }
    Ok(())
}

/// The first refresh without a new frame while the next frame renders: the one after the
/// refresh that showed the frame on screen, or refresh 0 for the warm-up frame.
fn first_held(screen: &OnScreen, period_ms: f64) -> usize {
    match screen.frame {
        Some(_) => refresh_at_or_after(screen.visible_ms, period_ms) as usize + 1,
        None => 0,
    }
}

/// The frame on screen while a run goes on.
struct OnScreen {
    frame: Option<usize>,
    visible_ms: f64,
    picture: Option<Rgb8Image>,
}

/// What the warm-up frames leave: the last of them on screen, the world time it showed and
/// how long it kept the machine busy, ms.
struct WarmUp {
    screen: OnScreen,
    lead_in_world_s: f64,
    last_busy_ms: f64,
}

/// The warm-up frames: one refresh apart on the path's time up to its start, each shown to
/// the controller and handed over, the clock told what each took.
fn warm_up(
    source: &mut dyn FrameSource,
    controller: &mut dyn Controller,
    sweep: &RealSweep,
    clock: &mut RealClock,
) -> Result<WarmUp> {
    let period = sweep.display.period_ms();
    let (mut warm_picture, mut lead_in_world_s, mut last_busy_ms) = (None, 0.0, 0.0);
    for k in (1..=sweep.warmup).rev() {
        let t_s = -f64::from(k) * period / 1000.0;
        lead_in_world_s = t_s;
        let at = PathPoint::Time { index: 0, t_s };
        let m = source.frame_within(at, controller.quality(), controller.frame_budget())?;
        let handed = source.hand_over()?;
        // A refused report (e.g. a 0 ms reading) leaves the controller as it was.
        let _ = controller.observe(&m.report);
        last_busy_ms = m.report.tp_ms + handed.ms;
        clock.expect(last_busy_ms);
        warm_picture = handed.image;
    }
    let screen = OnScreen {
        frame: None,
        visible_ms: 0.0,
        picture: warm_picture,
    };
    Ok(WarmUp {
        screen,
        lead_in_world_s,
        last_busy_ms,
    })
}

/// Runs `controller` under the real clock: warm-up frames leading up to the path's start, then frames
/// for as long as one starts before the run's end, each rendering the path at the time the
/// display model predicts it will be shown. Pictures of the frames on screen at the samples
/// `keep` asks for are kept (read back with the hand-over, outside the timing).
pub fn run_controller_real(
    source: &mut dyn FrameSource,
    controller: &mut dyn Controller,
    name: &str,
    sweep: &RealSweep,
    keep: Keep,
    progress: &ProgressBar,
) -> Result<ControllerRun> {
    controller.reset();
    progress.set_message(name.to_string());
    let mut clock = RealClock::new(sweep.display, sweep.duration_s)?;
    let (period, end) = (sweep.display.period_ms(), clock.duration_ms());
    let WarmUp {
        mut screen,
        lead_in_world_s,
        mut last_busy_ms,
    } = warm_up(source, controller, sweep, &mut clock)?;
    let mut pictures = BTreeMap::new();
    let (mut rows, mut records, mut world_s) = (Vec::new(), Vec::new(), Vec::new());
    let mut shown_ms = 0u64;
    let (started, mut rendering_ms) = (Instant::now(), 0.0);
    let mut warps = Warps::default();
    while let Some(slot) = clock.next_frame() {
        let q = controller.quality();
        let target_ms = controller.target_frame_ms();
        let predicted_ms = controller.decision().and_then(|d| d.predicted_ms);
        let ahead = if sweep.warp {
            let first = first_held(&screen, period);
            let count = warps_to_make(first, slot.start_ms, last_busy_ms, period);
            warps_ahead(source, (first, count), period, end, keep)
                .with_context(|| format!("{name}: before frame {}", slot.index))?
        } else {
            Vec::new()
        };
        let at = PathPoint::Time {
            index: slot.index,
            t_s: slot.world_s(),
        };
        let m = source
            .frame_within(at, q, controller.frame_budget())
            .with_context(|| format!("{name}: frame {} at {q} failed", slot.index))?;
        let handed = source.hand_over()?;
        last_busy_ms = m.report.tp_ms + handed.ms;
        let (used, held) = warps_used(&ahead, slot.start_ms, last_busy_ms, period, end);
        warps.missed += held - used;
        // Summed from +0 (a float sum of nothing is −0, which frames.csv would print).
        let warp_ms = ahead[..used].iter().fold(0.0, |sum, w| sum + w.ms);
        for w in ahead.into_iter().take(used) {
            warps.record(w.refresh, w.ms, w.picture);
        }
        let tp_ms = m.report.tp_ms;
        rendering_ms += tp_ms + warp_ms + handed.ms;
        if let Err(e) = controller.observe(&m.report) {
            log::warn!("{name}: frame {}: report refused: {e}", slot.index);
        }
        // The controller sees the frame's own time; the warps made meanwhile, on the same
        // machine, delay its completion on the display.
        let times = clock
            .present(tp_ms + warp_ms, handed.ms)
            .with_context(|| format!("{name}: frame {}", slot.index))?;
        if sweep.warp {
            warp_first_showing(source, &slot, &times, period, end, keep, &mut warps)
                .with_context(|| format!("{name}: frame {}", slot.index))?;
        }
        let before = std::mem::replace(
            &mut screen,
            OnScreen {
                frame: Some(slot.index),
                visible_ms: times.visible_ms,
                picture: handed.image,
            },
        );
        if keep.any_in(before.visible_ms, times.visible_ms, period, end)
            && let Some(picture) = before.picture
        {
            pictures.insert(before.frame, picture);
        }
        rows.push(
            FrameRow {
                target_ms,
                warp_ms,
                display: Some(times),
                ..FrameRow::measured(slot.index as u32, slot.world_s(), &m, sweep.band)
            }
            .with_decision(predicted_ms, controller.decision()),
        );
        records.push(FrameRecord {
            frame: slot.index,
            tp_ms,
            quality: q,
            rays: m.report.total_rays(),
        });
        world_s.push(slot.world_s());
        let now_ms = times.visible_ms.min(end) as u64;
        progress.inc(now_ms.saturating_sub(shown_ms));
        shown_ms = shown_ms.max(now_ms);
    }
    progress.inc((end as u64).saturating_sub(shown_ms));
    let wall_ms = started.elapsed().as_secs_f64() * 1e3;
    let busy_pct = source
        .takes_wall_time()
        .then(|| 100.0 * rendering_ms / wall_ms);
    if let Some(busy) = busy_pct {
        eprintln!(
            "bench: {name}: rendering and hand-over took {busy:.0} % of the run's {:.1} s of \
             wall time",
            wall_ms / 1e3
        );
    }
    if sweep.warp {
        // The last frame stays on screen to the end: every refresh after its own is warped.
        let first = first_held(&screen, period);
        let last = refresh_at_or_after(end, period) as usize;
        for refresh in first..last {
            let handed = source
                .warp(refresh as f64 * period / 1000.0, keep.wants(refresh))
                .with_context(|| format!("{name}: warp to refresh {refresh}"))?;
            warps.record(refresh, handed.ms, handed.image);
        }
    }
    if keep.any_in(screen.visible_ms, f64::INFINITY, period, end)
        && let Some(picture) = screen.picture
    {
        pictures.insert(screen.frame, picture);
    }
    let timeline = clock.finish();
    let summary = summarize(&records, sweep.band, sweep.bounds.max_quality(), None);
    Ok(ControllerRun {
        name: name.to_string(),
        band: sweep.band,
        rows,
        summary,
        flip: None,
        recorded: Vec::new(),
        budgeted: controller.frame_budget().is_some(),
        display: Some(DisplayRun {
            figures: DisplayFigures::of(&timeline),
            timeline,
            pictures,
            warps,
            world_s,
            lead_in_world_s,
            quality: None,
            busy_pct,
        }),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bench::displayed::time_key;
    use crate::bench::source::{HandOver, Measured, SIM_WARP_MS, SimulatedSource, simulated};
    use std::collections::BTreeSet;
    use steadyray_control::{Quality, Setup, from_name};
    use steadyray_display::SyncMode;
    use steadyray_render::{FrameBudget, SampleStream};

    /// The simulated source, recording the path times it is asked for, the Tp of each frame
    /// and the times of the warps.
    struct Recording {
        inner: SimulatedSource,
        times: Vec<f64>,
        tps: Vec<f64>,
        warps: Vec<f64>,
    }

    fn recording() -> Recording {
        Recording {
            inner: simulated(720),
            times: Vec::new(),
            tps: Vec::new(),
            warps: Vec::new(),
        }
    }

    impl FrameSource for Recording {
        fn describe(&self) -> (String, String) {
            self.inner.describe()
        }
        fn resolution(&self) -> (u32, u32) {
            self.inner.resolution()
        }
        fn path_duration_s(&self) -> f64 {
            self.inner.path_duration_s()
        }
        fn frame_within(
            &mut self,
            at: PathPoint,
            q: Quality,
            budget: Option<FrameBudget>,
        ) -> Result<Measured> {
            if let PathPoint::Time { t_s, .. } = at {
                self.times.push(t_s);
            }
            let m = self.inner.frame_within(at, q, budget)?;
            self.tps.push(m.report.tp_ms);
            Ok(m)
        }
        fn hand_over(&mut self) -> Result<HandOver> {
            self.inner.hand_over()
        }
        fn warp(&mut self, t_s: f64, picture: bool) -> Result<HandOver> {
            self.warps.push(t_s);
            self.inner.warp(t_s, picture)
        }
        fn takes_wall_time(&self) -> bool {
            self.inner.takes_wall_time()
        }
        fn load_changes(&self, n: u32) -> Option<Vec<usize>> {
            self.inner.load_changes(n)
        }
        fn last_picture(&mut self) -> Result<Option<Rgb8Image>> {
            self.inner.last_picture()
        }
        fn set_temporal(&mut self, on: bool) -> Result<()> {
            self.inner.set_temporal(on)
        }
        fn set_sample_stream(&mut self, stream: SampleStream) {
            self.inner.set_sample_stream(stream);
        }
    }

    #[test]
    fn warm_up_frames_lead_up_to_the_start_one_refresh_apart() {
        let mut source = recording();
        let bounds = Bounds::default();
        let setup = Setup::new(Band::PAPER, bounds, Quality::new(1.0, 4, 1.0)).unwrap();
        let mut controller = from_name("predictive", setup, "").unwrap();
        let sweep = RealSweep {
            display: DisplayConfig::new(50.0, SyncMode::Vsync).unwrap(),
            duration_s: 0.5,
            warmup: 4,
            band: Band::PAPER,
            bounds,
            warp: false,
        };
        let run = run_controller_real(
            &mut source,
            controller.as_mut(),
            "predictive",
            &sweep,
            Keep::Nothing,
            &ProgressBar::hidden(),
        )
        .unwrap();
        let (warm, counted) = source.times.split_at(4);
        assert_eq!(warm, [-0.08, -0.06, -0.04, -0.02]);
        assert_eq!(counted.len(), run.rows.len());
        assert!(counted.iter().all(|&t| t >= 0.0), "{counted:?}");
    }

    /// With warps, every refresh that shows no new frame (the warm-up frame's at the start,
    /// each frame's after its first) shows a warp, and each frame's time on the display is
    /// its render time plus the warps made while it rendered (those of the refreshes before
    /// it completed), while the controller sees its render time. A
    /// frame shown at another refresh than it rendered the world of is warped there when
    /// the warp fits before that refresh, and missed when it does not.
    #[test]
    fn warps_fill_the_refreshes_without_a_new_frame_inside_the_next_frames_time() {
        let mut source = recording();
        let bounds = Bounds::default();
        let setup = Setup::new(Band::PAPER, bounds, Quality::new(1.0, 4, 1.0)).unwrap();
        let mut controller = from_name("predictive", setup, "").unwrap();
        let display = DisplayConfig::new(60.0, SyncMode::Vsync).unwrap();
        let sweep = RealSweep {
            display,
            duration_s: 1.0,
            warmup: 4,
            band: Band::PAPER,
            bounds,
            warp: true,
        };
        let run = run_controller_real(
            &mut source,
            controller.as_mut(),
            "predictive",
            &sweep,
            Keep::Every(1),
            &ProgressBar::hidden(),
        )
        .unwrap();
        let shown = run.display.unwrap();
        let period = display.period_ms();
        let frames = shown.timeline.frames();
        let held: BTreeSet<usize> = shown
            .timeline
            .refreshes()
            .iter()
            .enumerate()
            .filter(|(_, r)| {
                r.frame
                    .is_none_or(|j| frames[j].visible_ms < r.time_ms - TIME_EPS_MS)
            })
            .map(|(i, _)| i)
            .collect();
        assert!(held.len() > 20, "the paper's band holds frames: {held:?}");
        let (mut first_showings, mut missed) = (BTreeSet::new(), 0);
        for (j, f) in frames.iter().enumerate() {
            let off_time = (f.visible_ms - 1000.0 * shown.world_s[j]).abs() > TIME_EPS_MS;
            if off_time && f.visible_ms < 1000.0 * sweep.duration_s - TIME_EPS_MS {
                if f.complete_ms() + SIM_WARP_MS <= f.visible_ms + TIME_EPS_MS {
                    first_showings.insert((f.visible_ms / period).round() as usize);
                } else {
                    missed += 1;
                }
            }
        }
        assert!(
            !first_showings.is_empty(),
            "some frames come off their predicted refresh"
        );
        let expected: BTreeSet<usize> = held.union(&first_showings).copied().collect();
        assert_eq!(shown.warps.shown, expected);
        assert_eq!(shown.warps.missed, missed);
        assert!(shown.warps.ms.iter().all(|&ms| ms == SIM_WARP_MS));
        // The simulated source has no pictures to keep.
        assert!(shown.warps.pictures.is_empty());
        let rendered = &source.tps[4..];
        for (j, f) in frames.iter().enumerate() {
            let made_meanwhile = held
                .iter()
                .filter(|&&i| {
                    let t = i as f64 * period;
                    t >= f.start_ms - TIME_EPS_MS && t < f.complete_ms() - TIME_EPS_MS
                })
                .count();
            let expected = rendered[j] + SIM_WARP_MS * made_meanwhile as f64;
            assert!(
                (f.tp_ms - expected).abs() < 1e-9,
                "frame {j}: Tp {} against {} rendered and {made_meanwhile} warps",
                f.tp_ms,
                rendered[j]
            );
            assert_eq!(
                run.rows[j].tp_ms, rendered[j],
                "the controller's Tp, frame {j}"
            );
            assert_eq!(
                run.rows[j].warp_ms,
                SIM_WARP_MS * made_meanwhile as f64,
                "frame {j}"
            );
        }
        let warp_times: BTreeSet<i64> = source.warps.iter().map(|&t| time_key(t)).collect();
        assert!(
            held.iter()
                .all(|&i| warp_times.contains(&time_key(i as f64 * period / 1000.0))),
            "each warp shows its refresh's time"
        );
    }

    /// Warps made ahead of a frame from refresh 1 (P = 10 ms) at `ms` each.
    fn ahead(ms: f64) -> Vec<Ahead> {
        (1..=WARPS_AHEAD)
            .map(|refresh| Ahead {
                refresh,
                ms,
                picture: None,
            })
            .collect()
    }

    #[test]
    fn warps_are_made_for_the_refreshes_a_frame_as_slow_as_the_last_would_hold_and_one_more() {
        // P = 10 ms; the frame starts at 2 ms and may leave refreshes from 1 (10 ms) held.
        // The last took 7 ms: this one would complete at 9 ms and hold none; one warp.
        assert_eq!(warps_to_make(1, 2.0, 7.0, 10.0), 1);
        // 18 ms (complete at 20 ms, refresh 2 shows it): refresh 1 held, two warps.
        assert_eq!(warps_to_make(1, 2.0, 18.0, 10.0), 2);
        // 19 ms: held over refreshes 1 and 2, three warps.
        assert_eq!(warps_to_make(1, 2.0, 19.0, 10.0), 3);
        // Never more than WARPS_AHEAD, however slow.
        assert_eq!(warps_to_make(1, 2.0, 500.0, 10.0), WARPS_AHEAD);
        // The warm-up frame's refreshes start at 0.
        assert_eq!(warps_to_make(0, 0.0, 15.0, 10.0), 3);
    }

    #[test]
    fn a_warp_never_costs_a_frame_its_refresh() {
        // A frame from 0 busy for 25 ms leaves refreshes 1 and 2 (10, 20 ms) without a new
        // frame and makes refresh 3 (30 ms).
        assert_eq!(warps_used(&ahead(2.0), 0.0, 25.0, 10.0, 1e9), (2, 2));
        // Two 4 ms warps would complete it at 33 ms: only the first is made.
        assert_eq!(warps_used(&ahead(4.0), 0.0, 25.0, 10.0, 1e9), (1, 2));
        // A warp slower than a refresh is never made: it would cascade.
        assert_eq!(warps_used(&ahead(12.0), 0.0, 25.0, 10.0, 1e9), (0, 2));
        // A frame done before refresh 1 leaves none; one of 75 ms leaves 7, 4 of them made.
        assert_eq!(warps_used(&ahead(1.0), 0.0, 8.0, 10.0, 1e9), (0, 0));
        assert_eq!(warps_used(&ahead(1.0), 0.0, 75.0, 10.0, 1e9), (4, 7));
        // Refreshes from the run's end on do not count.
        assert_eq!(warps_used(&ahead(1.0), 0.0, 75.0, 10.0, 25.0), (2, 2));
        assert_eq!(warps_used(&[], 0.0, 75.0, 10.0, 1e9), (0, 0));
    }

    #[test]
    fn kept_samples_in_a_span() {
        let p = 10.0;
        let every2 = Keep::Every(2);
        let kept: Vec<usize> = (0..12).filter(|&i| every2.wants(i)).collect();
        assert_eq!(kept, [0, 3, 4, 7, 8, 11]);
        assert!(every2.any_in(0.0, 5.0, p, 100.0), "sample 0");
        assert!(
            !every2.any_in(5.0, 30.0, p, 100.0),
            "samples 1 and 2 are not kept"
        );
        assert!(every2.any_in(5.0, 30.5, p, 100.0), "sample 3 at 30");
        assert!(
            !every2.any_in(95.0, f64::INFINITY, p, 100.0),
            "after the end"
        );
        assert!(
            Keep::Every(1).any_in(10.0, 10.5, p, 100.0),
            "a frame shown at a sample"
        );
        assert!(!Keep::Nothing.any_in(0.0, 100.0, p, 100.0));
        assert!(Keep::Every(1).wants(5) && !Keep::Nothing.wants(0));
    }

    /// Frames shown for two or three refreshes each are seen at every refresh of their
    /// showing, in near-equal shares, whatever K samples one refresh in.
    #[test]
    fn kept_samples_do_not_alias_with_held_frames() {
        for k in 1..=6u32 {
            for held in 2..=3usize {
                let mut seen = vec![0; held];
                for i in (0..held * 72).filter(|&i| Keep::Every(k).wants(i)) {
                    seen[i % held] += 1;
                }
                let (lo, hi) = (*seen.iter().min().unwrap(), *seen.iter().max().unwrap());
                assert!(
                    lo > 0 && hi - lo <= 1 + hi / 4,
                    "K = {k}, frames held {held} refreshes: {seen:?}"
                );
            }
        }
    }
}
