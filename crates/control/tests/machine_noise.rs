//! Controllers against the simulated renderer replaying the timing noise recorded on real
//! machines (`crates/control/noise/*.json`, see `steadyray_control::noise`): jitter, spikes
//! and spells of slower and faster speed. Deterministic, on the fake clock. Run with
//! `--nocapture` to see the figures.

use std::path::PathBuf;
use steadyray_control::metrics::{FrameRecord, RunSummary, summarize};
use steadyray_control::noise::{NoiseProcess, NoiseProfile, fit_profile};
use steadyray_control::simulate::{LoadProfile, RendererModel, SimRenderer, corridor_load, run};
use steadyray_control::{Band, Bounds, Quality, Setup, aim_ceiling, from_name};

const BAND: Band = Band::PAPER;
const FRAMES: usize = 720;
const WARM_UP: usize = 20;
const SEEDS: std::ops::RangeInclusive<u64> = 1..=5;

/// Every recorded profile in the repository, with its file name.
fn recorded_profiles() -> Vec<(String, NoiseProfile)> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("noise");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    assert!(
        !files.is_empty(),
        "no recorded profiles in {}",
        dir.display()
    );
    files
        .into_iter()
        .map(|path| {
            let text = std::fs::read_to_string(&path).unwrap();
            let profile: NoiseProfile = serde_json::from_str(&text).unwrap();
            profile.validate().unwrap();
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            (name, profile)
        })
        .collect()
}

fn top() -> Quality {
    Bounds::default().max_quality()
}

/// `name` over the counted lap of the corridor sweep (after a warm-up lap's first frames),
/// the model's own Gaussian noise replaced by `profile`.
fn corridor_sweep(name: &str, profile: &NoiseProfile, seed: u64) -> RunSummary {
    let mut model = RendererModel::corridor(FRAMES).with_machine_noise(profile.clone());
    model.noise = 0.0;
    model.seed = seed;
    let setup = Setup::new(BAND, Bounds::default(), top()).unwrap();
    let mut c = from_name(name, setup, "").unwrap();
    let records = run(c.as_mut(), &model, FRAMES + WARM_UP);
    let s = summarize(&records[WARM_UP..], BAND, top(), Some(&[]));
    println!(
        "{name:10} {:24} seed {seed}: ok {:5.1}% in {:5.1}% over {:4.1}% under {:4.1}% \
         rev/100 {:4.2} changes {:3}",
        profile.machine,
        s.ok_pct,
        s.in_band_pct,
        s.over_pct,
        s.under_pct,
        s.reversals_per_100,
        s.quality_changes
    );
    s
}

/// Where perfect aim would keep at least this share of frames in the band (%), a controller
/// is held to the 97 %; a machine whose noise alone throws more frames out (the
/// shared recordings: 69 to 79 %) is held to its perfect aim less a margin instead.
const HOLDABLE_PCT: f64 = 97.5;

/// The profiles whose noise lets a controller keep 97 % in the band.
fn holdable_profiles() -> Vec<(String, NoiseProfile)> {
    let holdable: Vec<_> = recorded_profiles()
        .into_iter()
        .filter(|(_, p)| perfect_aim_pct(p) >= HOLDABLE_PCT)
        .collect();
    assert!(
        !holdable.is_empty(),
        "no recorded profile a controller can hold"
    );
    holdable
}

/// With every recorded machine's noise that allows it, `predictive` keeps at least 97 % of
/// the corridor sweep's frames in the band (or under it at the highest quality, where
/// nothing more can be drawn) with at most 3 reversals per 100 frames, on every seed.
#[test]
fn predictive_holds_the_corridor_under_each_recorded_noise() {
    for (file, profile) in holdable_profiles() {
        for seed in SEEDS {
            let s = corridor_sweep("predictive", &profile, seed);
            assert!(s.ok_pct >= 97.0, "{file} seed {seed}: {s:?}");
            assert!(s.reversals_per_100 <= 3.0, "{file} seed {seed}: {s:?}");
        }
    }
}

/// With a frame budget (`budget=true`: the renderer stops adding samples before the band's
/// top and fills a frame that would end early), `predictive` keeps at least 97 % of the
/// corridor sweep's frames in the band, or under it having drawn the most the bounds allow
/// (S filled to its highest, at the highest R and scale), under every recorded machine's
/// noise, the shared VM's too, where per-frame control alone cannot (its perfect aim: 69 to
/// 79 %), with at most 3 reversals of its planned quality per 100 frames where the noise
/// lets per-frame control hold the band ([`REVERSALS_ON_SHARED_NOISE`] elsewhere).
#[test]
fn predictive_with_a_frame_budget_holds_the_corridor_under_every_recorded_noise() {
    for (file, profile) in recorded_profiles() {
        for seed in SEEDS {
            let mut model = RendererModel::corridor(FRAMES).with_machine_noise(profile.clone());
            model.noise = 0.0;
            model.seed = seed;
            let setup = Setup::new(BAND, Bounds::default(), top()).unwrap();
            let mut c = from_name("predictive", setup, "budget=true").unwrap();
            let mut renderer = SimRenderer::new(model.clone());
            let (mut records, mut ok) = (Vec::new(), 0);
            for frame in 0..FRAMES + WARM_UP {
                let q = c.quality();
                let budget = c.frame_budget();
                let load = model.profile.load(frame);
                let report = renderer.render_within(frame, &load, q, budget.as_ref());
                let drew_the_most = report.quality.spp >= top().spp
                    && q.depth == top().depth
                    && q.scale == top().scale;
                if frame >= WARM_UP
                    && (BAND.contains(report.tp_ms)
                        || (report.tp_ms < BAND.tmin_ms() && drew_the_most))
                {
                    ok += 1;
                }
                let _ = c.observe(&report);
                records.push(FrameRecord {
                    frame,
                    tp_ms: report.tp_ms,
                    quality: q,
                    rays: report.total_rays(),
                });
            }
            let s = summarize(&records[WARM_UP..], BAND, top(), Some(&[]));
            let ok_pct = 100.0 * f64::from(ok) / FRAMES as f64;
            println!(
                "budget {:40} seed {seed}: ok {ok_pct:5.1}% over {:4.1}% rev/100 {:4.2}",
                profile.machine, s.over_pct, s.reversals_per_100
            );
            assert!(ok_pct >= 97.0, "{file} seed {seed}: {ok_pct} {s:?}");
            let reversals = if perfect_aim_pct(&profile) >= HOLDABLE_PCT {
                3.0
            } else {
                REVERSALS_ON_SHARED_NOISE
            };
            assert!(
                s.reversals_per_100 <= reversals,
                "{file} seed {seed}: {s:?}"
            );
        }
    }
}

/// Under the shared VM's recorded noise the budget holds the band but its planned quality
/// still follows the noise: 0.3 to 5 reversals per 100 frames over the seeds (a guard on
/// the figures reached, not the 3 met).
const REVERSALS_ON_SHARED_NOISE: f64 = 6.0;

/// The same for `hysteresis`, which needs no cost model: the band kept at 95 %.
#[test]
fn hysteresis_holds_the_corridor_under_each_recorded_noise() {
    for (file, profile) in holdable_profiles() {
        for seed in SEEDS {
            let s = corridor_sweep("hysteresis", &profile, seed);
            assert!(s.ok_pct >= 95.0, "{file} seed {seed}: {s:?}");
            assert!(s.reversals_per_100 <= 3.0, "{file} seed {seed}: {s:?}");
        }
    }
}

/// One slow frame (1.25 to 1.6 times its time, the spikes the recorded machines make) on a
/// steady view: `predictive` and `hysteresis` may trim the quality, but the next frame, back
/// at normal speed, still lands in the band; a cut on one frame's word that drops the next
/// frame under the band was a miss and, with the raise that follows, a reversal.
#[test]
fn a_spike_alone_does_not_cut_under_the_band() {
    for (name, factor) in ["predictive", "hysteresis"]
        .into_iter()
        .flat_map(|name| [1.25, 1.3, 1.45, 1.6].map(|f| (name, f)))
    {
        let mut model =
            RendererModel::corridor(FRAMES).with_profile(LoadProfile::Constant(corridor_load(0.6)));
        model.spike_factor = factor;
        model.spike_frames = vec![100, 160, 220];
        let setup = Setup::new(BAND, Bounds::default(), top()).unwrap();
        let mut c = from_name(name, setup, "").unwrap();
        let records = run(c.as_mut(), &model, 260);
        for &f in &model.spike_frames {
            let (spike, next) = (&records[f], &records[f + 1]);
            assert!(spike.tp_ms > BAND.tmax_ms(), "{name} {factor}: {spike:?}");
            assert!(
                BAND.contains(next.tp_ms),
                "{name} {factor}, frame {f}: {spike:?} then {next:?}"
            );
        }
        let s = summarize(&records[50..], BAND, top(), Some(&[]));
        // `hysteresis` trims on the spike and raises back after three frames with headroom.
        let reversals = if name == "predictive" { 1.0 } else { 3.0 };
        assert!(s.reversals_per_100 <= reversals, "{name} {factor}: {s:?}");
    }
}

/// The share of frames (%) that a controller aiming perfectly would keep in `BAND` under
/// `profile`'s jitter and spikes, its spells tracked exactly: the aim ceiling of 20,000
/// drawn factors.
fn perfect_aim_pct(profile: &NoiseProfile) -> f64 {
    let jitter_only = NoiseProfile {
        spell_sigma: 0.0,
        ..profile.clone()
    };
    let mut noise = NoiseProcess::new(jitter_only, 99);
    let factors = (0..20_000).map(|_| noise.factor(20.0));
    aim_ceiling(factors, BAND)
        .expect("20,000 factors")
        .in_band_pct
}

/// A steady view whose frames the band can hold, under each recorded machine's noise:
/// where the noise allows 97 %, `predictive` keeps within 2.5 points of what perfect aim
/// would (spells tracked exactly) with at most 3 reversals per 100 frames (the idle VM's
/// recording, whose spikes come one frame in thirteen, is where the half point beyond 2
/// goes: 96.0 against 98.4 on its worst seed, the controller before issue 47's aim 96.3). Under the shared
/// machine's noise (frames scattering by 12 to 14 % and the speed by 30 % in spells under
/// a second) it stays within 20 points of perfect aim with at most 9 reversals per 100: a
/// guard on the figures reached (5 to 9), not a target met; the controller before the
/// spike and drift rules made 10 to 16 here.
#[test]
fn predictive_keeps_near_perfect_aim_on_a_steady_view_under_each_noise() {
    for (file, profile) in recorded_profiles() {
        let bound = perfect_aim_pct(&profile);
        let (margin, reversals) = if bound >= HOLDABLE_PCT {
            (2.5, 3.0)
        } else {
            (20.0, 9.0)
        };
        for seed in SEEDS {
            let mut model = RendererModel::corridor(FRAMES)
                .with_profile(LoadProfile::Constant(corridor_load(0.6)))
                .with_machine_noise(profile.clone());
            model.noise = 0.0;
            model.seed = seed;
            let setup = Setup::new(BAND, Bounds::default(), top()).unwrap();
            let mut c = from_name("predictive", setup, "").unwrap();
            let records = run(c.as_mut(), &model, FRAMES);
            let s = summarize(&records[WARM_UP..], BAND, top(), Some(&[]));
            println!(
                "steady view {file:40} seed {seed}: in {:5.1}% (perfect aim {bound:5.1}%) \
                 rev/100 {:4.2}",
                s.in_band_pct, s.reversals_per_100
            );
            assert!(s.in_band_pct >= bound - margin, "{file} seed {seed}: {s:?}");
            assert!(
                s.reversals_per_100 <= reversals,
                "{file} seed {seed}: {s:?}"
            );
        }
    }
}

/// A fixed-quality sweep of the simulated renderer under each recorded profile, fitted as
/// the bench's runs are (two runs of the same frames), gives the profile back: what the
/// tests replay is what the recordings measured.
#[test]
fn each_recorded_profile_survives_a_round_trip_through_the_fit() {
    for (file, profile) in recorded_profiles() {
        let sweep = |seed: u64| {
            let mut model = RendererModel::corridor(4 * FRAMES).with_machine_noise(profile.clone());
            model.noise = 0.0;
            model.timer_ms = 0.0;
            model.seed = seed;
            let mut c = from_name(
                "fixed",
                Setup::new(BAND, Bounds::default(), Quality::new(2.0, 16, 1.0)).unwrap(),
                "",
            )
            .unwrap();
            let records = run(c.as_mut(), &model, 4 * FRAMES);
            records.iter().map(|r| r.tp_ms).collect::<Vec<f64>>()
        };
        let fit = fit_profile(&sweep(1), Some(&sweep(2)), 3.0, "", "").unwrap();
        let got = &fit.profile;
        println!(
            "{file}: {got:?} neighbours {:?} runs {:?}",
            fit.neighbour_ratio, fit.run_ratio
        );
        let near = |a: f64, b: f64, tol: f64| (a - b).abs() <= tol * b.max(1e-9);
        // A jitter under 1 % (the idle VM's) is fitted to within 0.3 % of a frame: below
        // that the fit cannot part the jitter from the small spikes' tails.
        assert!(
            near(got.jitter_sigma, profile.jitter_sigma, 0.25)
                || (got.jitter_sigma - profile.jitter_sigma).abs() <= 0.003,
            "{file}: {got:?}"
        );
        assert!(
            near(got.spell_sigma, profile.spell_sigma, 0.5),
            "{file}: {got:?}"
        );
    }
}
