//! The display model on hand-made timings, against answers computed by hand.

use proptest::prelude::*;
use steadyray_display::{
    DisplayConfig, DisplayError, DisplayFigures, FrameSlot, FrameTimes, PREDICTION_FRAMES,
    RealClock, SyncMode, Timeline, VrrRange,
};

/// 60 Hz: the refresh period P, ms.
const P: f64 = 1000.0 / 60.0;

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

/// Runs `duration_s` of frames taking `times[j % len]` (Tp, hand-over) on `config`; checks
/// that each frame's predicted show time is when it was shown whenever its busy time is the
/// predicted one.
fn run(config: DisplayConfig, duration_s: f64, times: &[(f64, f64)]) -> Timeline {
    run_slots(config, duration_s, |j| times[j % times.len()]).0
}

/// Runs `duration_s` of frames, frame j taking `time(j)` (Tp, hand-over), on `config`;
/// returns the timeline and each frame's slot, with the check of [`run`].
fn run_slots(
    config: DisplayConfig,
    duration_s: f64,
    time: impl Fn(usize) -> (f64, f64),
) -> (Timeline, Vec<FrameSlot>) {
    let mut clock = RealClock::new(config, duration_s).unwrap();
    let mut slots = Vec::new();
    while let Some(slot) = clock.next_frame() {
        let (tp, hand_over) = time(slot.index);
        let predicted = clock.predicted_busy_ms();
        let frame = clock.present(tp, hand_over).unwrap();
        assert!(close(frame.start_ms, slot.start_ms));
        if close(predicted, tp + hand_over) {
            assert!(close(frame.visible_ms, slot.show_ms), "{slot:?} {frame:?}");
        }
        slots.push(slot);
    }
    (clock.finish(), slots)
}

/// How many refreshes after the world time it renders each frame was shown (negative: ahead).
fn lateness(timeline: &Timeline, slots: &[FrameSlot]) -> Vec<i64> {
    timeline
        .frames()
        .iter()
        .zip(slots)
        .map(|(f, s)| ((f.visible_ms - s.show_ms) / P).round() as i64)
        .collect()
}

fn vsync(hz: f64) -> DisplayConfig {
    DisplayConfig::new(hz, SyncMode::Vsync).unwrap()
}

#[test]
fn ten_ms_frames_at_60_hz_repeat_no_refresh() {
    let t = run(vsync(60.0), 1.0, &[(10.0, 0.0)]);
    // Frame j starts at refresh j and shows at refresh j + 1.
    for (j, f) in t.frames().iter().enumerate() {
        assert!(close(f.start_ms, j as f64 * P) && close(f.visible_ms, (j + 1) as f64 * P));
    }
    assert_eq!(t.refreshes().len(), 60);
    let f = DisplayFigures::of(&t);
    assert_eq!(f.frames_rendered, 60);
    // Refresh 0 shows nothing yet; refreshes 1 to 59 each show a new frame.
    assert_eq!(f.frames_shown, 59);
    assert!(close(f.displayed_fps, 59.0));
    assert_eq!(f.repeated_pct, 0.0);
    assert!(f.pacing_std_ms.unwrap() < 1e-9);
    assert!(close(f.latency_ms_mean.unwrap(), P) && close(f.latency_ms_p95.unwrap(), P));
}

#[test]
fn seventeen_ms_frames_show_every_second_refresh() {
    let t = run(vsync(60.0), 1.0, &[(17.0, 0.0)]);
    for (j, f) in t.frames().iter().enumerate() {
        assert!(
            close(f.visible_ms, (2 * j + 2) as f64 * P),
            "frame {j}: {f:?}"
        );
    }
    let shown: Vec<Option<usize>> = t.refreshes().iter().map(|r| r.frame).collect();
    assert_eq!(shown[..6], [None, None, Some(0), Some(0), Some(1), Some(1)]);
    let f = DisplayFigures::of(&t);
    assert_eq!((f.frames_rendered, f.frames_shown), (30, 29));
    assert!(close(f.displayed_fps, 29.0));
    // Refreshes 2..=59 show frames: 57 consecutive pairs, 29 of them (3, 5, ..., 59) repeats.
    assert!(close(f.repeated_pct, 100.0 * 29.0 / 57.0));
    assert!(f.pacing_std_ms.unwrap() < 1e-9);
    assert!(close(f.latency_ms_mean.unwrap(), 2.0 * P));
}

#[test]
fn latency_and_pacing_equal_the_hand_computed_figures() {
    // Tp 10, 20, 10, 5, 10 ms, each with 1 ms of hand-over, over 100 ms at 60 Hz:
    // frame 0: s 0, c 11, v P; frame 1: s P, c P + 21, v 3P; frame 2: s 3P, c 3P + 11, v 4P;
    // frame 3: s 4P, c 4P + 6, v 5P; frame 4: s 5P, c 5P + 11, v 6P = 100 ms, the end.
    let times = [
        (10.0, 1.0),
        (20.0, 1.0),
        (10.0, 1.0),
        (5.0, 1.0),
        (10.0, 1.0),
    ];
    let t = run(vsync(60.0), 0.1, &times);
    let visible: Vec<f64> = t.frames().iter().map(|f| f.visible_ms / P).collect();
    assert_eq!(visible.len(), 5);
    for (v, expected) in visible.iter().zip([1.0, 3.0, 4.0, 5.0, 6.0]) {
        assert!((v - expected).abs() < 1e-9, "{visible:?}");
    }
    assert!(close(t.frames()[1].complete_ms(), P + 21.0));
    let shown: Vec<Option<usize>> = t.refreshes().iter().map(|r| r.frame).collect();
    assert_eq!(shown, [None, Some(0), Some(0), Some(1), Some(2), Some(3)]);
    let f = DisplayFigures::of(&t);
    assert_eq!((f.frames_rendered, f.frames_shown), (5, 4));
    assert!(close(f.displayed_fps, 40.0));
    assert!(close(f.repeated_pct, 25.0));
    // Latencies P, 2P, P, P: mean 5P/4; p95 at rank 0.95·3 = 2.85 of [P, P, P, 2P]: 1.85 P.
    assert!(close(f.latency_ms_mean.unwrap(), 1.25 * P));
    assert!(close(f.latency_ms_p95.unwrap(), 1.85 * P));
    // Intervals 2P, P, P: standard deviation P·√2/3.
    assert!(close(f.pacing_std_ms.unwrap(), P * 2f64.sqrt() / 3.0));
}

#[test]
fn one_slow_frame_leaves_the_next_frames_on_time() {
    // 10 ms frames, one of 25 ms (frame 6): it misses its refresh and is shown one late; the
    // frames after it are predicted from the median, not from it, so each is shown at the
    // world time it rendered, and no world time is rendered twice.
    let (t, slots) = run_slots(vsync(60.0), 0.5, |j| {
        (if j == 6 { 25.0 } else { 10.0 }, 0.0)
    });
    let late = lateness(&t, &slots);
    assert_eq!(late[6], 1, "{late:?}");
    assert!(
        late.iter().enumerate().all(|(j, &l)| j == 6 || l == 0),
        "{late:?}"
    );
    assert!(slots.windows(2).all(|w| w[1].show_ms > w[0].show_ms));
}

#[test]
fn a_lasting_slowdown_is_followed_within_a_few_frames() {
    // 10 ms frames, then 25 ms from frame 6 on: late until most of the last five frames are
    // slow, then on time again.
    let (t, slots) = run_slots(vsync(60.0), 1.0, |j| (if j < 6 { 10.0 } else { 25.0 }, 0.0));
    let late = lateness(&t, &slots);
    let settled = 6 + PREDICTION_FRAMES / 2 + 1;
    assert!(late[6..settled].iter().all(|&l| l == 1), "{late:?}");
    assert!(
        late.iter()
            .enumerate()
            .all(|(j, &l)| (6..settled).contains(&j) || l == 0),
        "{late:?}"
    );
}

#[test]
fn the_prediction_is_the_median_of_the_recent_frames() {
    let mut clock = RealClock::new(vsync(60.0), 1.0).unwrap();
    assert_eq!(clock.predicted_busy_ms(), 0.0);
    clock.expect(8.0);
    clock.expect(f64::NAN);
    clock.expect(-1.0);
    assert_eq!(clock.predicted_busy_ms(), 8.0);
    clock.expect(12.0);
    assert_eq!(clock.predicted_busy_ms(), 10.0);
    for busy in [30.0, 9.0, 11.0] {
        clock.present(busy, 0.0).unwrap();
    }
    // 8, 12, 30, 9, 11.
    assert_eq!(clock.predicted_busy_ms(), 11.0);
    clock.present(40.0, 0.0).unwrap();
    // The oldest (8) leaves: 12, 30, 9, 11, 40.
    assert_eq!(clock.predicted_busy_ms(), 12.0);
}

#[test]
fn vsync_off_shows_a_frame_at_its_completion() {
    let config = DisplayConfig::new(60.0, SyncMode::Off).unwrap();
    let t = run(config, 0.1, &[(9.0, 1.0)]);
    for (j, f) in t.frames().iter().enumerate() {
        assert!(close(f.visible_ms, f.complete_ms()));
        assert!(close(f.visible_ms, 10.0 * (j + 1) as f64));
    }
    assert_eq!(t.frames().len(), 10);
    // The panel still scans at 60 Hz: at 16.7, 33.3, 50, 66.7 and 83.3 ms the latest frame
    // complete is frame 0 (10 ms), 2 (30), 4 (50), 5 (60) and 7 (80).
    let shown: Vec<Option<usize>> = t.refreshes().iter().map(|r| r.frame).collect();
    assert_eq!(shown, [None, Some(0), Some(2), Some(4), Some(5), Some(7)]);
    let f = DisplayFigures::of(&t);
    assert_eq!(f.frames_shown, 5);
    assert!(close(f.displayed_fps, 50.0));
    assert_eq!(f.repeated_pct, 0.0);
    assert!(close(f.latency_ms_mean.unwrap(), 10.0));
}

#[test]
fn variable_refresh_shows_a_frame_at_its_completion_within_its_range() {
    // A 40-100 Hz panel: refreshes 10 to 25 ms apart.
    let range = VrrRange::new(40.0, 100.0).unwrap();
    let config = DisplayConfig::new(100.0, SyncMode::Vrr(range)).unwrap();
    // Frame 0: c 12, shown at 12. Frame 1: s 12, c 16, but not before 12 + 10 = 22.
    // Frame 2: s 22, c 52: the panel repeats frame 1 at 47 and shows frame 2 at 57.
    // Frame 3: s 57, c 77, shown at 77. Frame 4: s 77, c 127, after the end.
    let times = [
        (12.0, 0.0),
        (3.0, 1.0),
        (30.0, 0.0),
        (20.0, 0.0),
        (50.0, 0.0),
    ];
    let t = run(config, 0.1, &times);
    let visible: Vec<f64> = t.frames().iter().map(|f| f.visible_ms).collect();
    assert_eq!(visible, [12.0, 22.0, 57.0, 77.0, 127.0]);
    let refreshes: Vec<(f64, Option<usize>)> =
        t.refreshes().iter().map(|r| (r.time_ms, r.frame)).collect();
    assert_eq!(
        refreshes,
        [
            (0.0, None),
            (12.0, Some(0)),
            (22.0, Some(1)),
            (47.0, Some(1)),
            (57.0, Some(2)),
            (77.0, Some(3))
        ]
    );
    let f = DisplayFigures::of(&t);
    assert_eq!((f.frames_rendered, f.frames_shown), (5, 4));
    assert!(close(f.repeated_pct, 25.0));
    // Latencies 12, 10, 35, 20.
    assert!(close(f.latency_ms_mean.unwrap(), 19.25));
}

#[test]
fn the_screen_sampled_at_another_rate() {
    let t = run(vsync(60.0), 0.1, &[(10.0, 0.0)]);
    // Frames show at P, 2P, ...: sampled at 30 Hz (every 2P) the screen shows frames 1, 3.
    let sampled: Vec<Option<usize>> = t.sampled(2.0 * P).iter().map(|r| r.frame).collect();
    assert_eq!(sampled, [None, Some(1), Some(3)]);
    assert_eq!(t.shown_at(-1.0), None);
    assert_eq!(t.shown_at(P - 0.5), None);
    assert_eq!(t.shown_at(P), Some(0));
    assert_eq!(t.shown_at(1e9), Some(t.frames().len() - 1));
    // Sampled at the refresh rate with vsync on: exactly the panel's refreshes.
    assert_eq!(t.sampled(P), t.refreshes());
}

#[test]
fn bad_settings_and_times_are_refused_with_the_value_named() {
    for hz in [0.0, -60.0, f64::NAN, f64::INFINITY, 2000.0] {
        let err = DisplayConfig::new(hz, SyncMode::Vsync).unwrap_err();
        assert!(matches!(err, DisplayError::BadRefresh(_)), "{hz}: {err}");
    }
    for text in ["60-48", "0-60", "48", "a-b", "48-2000", "-"] {
        let err = text.parse::<VrrRange>().unwrap_err().to_string();
        assert!(err.contains("MIN-MAX"), "{text}: {err}");
    }
    assert_eq!(
        "48-144".parse::<VrrRange>().unwrap(),
        VrrRange::new(48.0, 144.0).unwrap()
    );
    for s in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e6] {
        let err = RealClock::new(vsync(60.0), s).unwrap_err();
        assert!(err.to_string().contains("duration"), "{s}: {err}");
    }
    let mut clock = RealClock::new(vsync(60.0), 0.02).unwrap();
    for (tp, hand_over) in [
        (f64::NAN, 0.0),
        (-1.0, 0.0),
        (1.0, f64::INFINITY),
        (0.0, 0.0),
    ] {
        let err = clock.present(tp, hand_over).unwrap_err();
        assert!(matches!(err, DisplayError::BadFrameTime { .. }), "{err}");
    }
    assert!(
        clock.next_frame().is_some(),
        "a refused frame changes nothing"
    );
    clock.present(10.0, 0.0).unwrap();
    clock.present(10.0, 0.0).unwrap();
    assert!(clock.next_frame().is_none());
    let err = clock.present(10.0, 0.0).unwrap_err();
    assert!(matches!(err, DisplayError::RunOver { .. }), "{err}");
}

proptest! {
    /// Whatever the frame times, with vsync on: frames show on refreshes, one refresh at most
    /// each, never before they are complete, and the run shows at most one frame a refresh.
    #[test]
    fn vsync_invariants(times in prop::collection::vec((0.1f64..80.0, 0.0f64..3.0), 1..20)) {
        let t = run(vsync(60.0), 0.5, &times);
        let mut previous: Option<FrameTimes> = None;
        for f in t.frames() {
            let i = f.visible_ms / P;
            prop_assert!((i - i.round()).abs() < 1e-9);
            prop_assert!(f.visible_ms >= f.complete_ms() - 1e-9);
            if let Some(p) = previous {
                prop_assert!(f.visible_ms > p.visible_ms + 0.5 * P);
                prop_assert!(close(f.start_ms, p.visible_ms));
            }
            previous = Some(*f);
        }
        let f = DisplayFigures::of(&t);
        prop_assert!(f.displayed_fps <= 60.0 + 1e-9);
        prop_assert!(f.frames_shown <= f.frames_rendered);
    }
}
