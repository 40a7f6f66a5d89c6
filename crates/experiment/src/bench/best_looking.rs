//! The best-looking fixed quality (`bench --clock real --quality`): of a small set of fixed
//! qualities, each run on the real clock for the same span of display time as every other
//! run and scored by its displayed FLIP (the table's `displayed FLIP`, lower is better), the
//! one that looked best. Where the most-in-band fixed quality is the one fixed choice that
//! holds the band best, this is the one fixed choice a controller has to out-look.
//!
//! The candidates are nine points of the grid S ∈ {1, 2, 4}, R ∈ {2, 4, 16}, scale ∈
//! {0.5, 0.75, 1}: an orthogonal array, so every level of each knob is tried three times and
//! every pair of levels of two knobs once. They span the cheapest (S = 1, R = 2, ×0.5) to
//! the richest (S = 4, R = 16, ×0.75; S = 4, R = 2 at full scale), and include the paper's
//! S = 1, R = 16 at full scale. Each is clamped to the bench's bounds (duplicates dropped).
//! The search costs one display span per candidate, its displayed quality measured at once
//! against the references every run shares, so only one candidate's pictures are held at a
//! time. JOD is scored after the bench (`steadyray jod`), so it cannot choose: the winner's
//! JOD is reported like any run's.

use steadyray_control::{Bounds, Quality};

/// Which runs of the best-looking fixed quality the bench makes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BestLookingFixed {
    /// Where the bench measures the displayed quality (`--clock real --quality`): once per
    /// temporal mode, after the first `fixed` of `--controllers` (and its most-in-band fixed
    /// quality).
    #[default]
    WithFixed,
    /// Never (`--no-best-looking-fixed`).
    Skip,
    /// It alone, once per temporal mode, and none of `--controllers`
    /// (`--only-best-looking-fixed`, which needs `--clock real --quality`).
    Only,
}

/// The label of the best-looking fixed runs, before their quality.
pub const LABEL: &str = "best-looking fixed";

/// S of the candidates.
const SPP: [f32; 3] = [1.0, 2.0, 4.0];
/// R of the candidates.
const DEPTH: [u32; 3] = [2, 4, 16];
/// Resolution scales of the candidates.
const SCALE: [f32; 3] = [0.5, 0.75, 1.0];

/// The candidates within `bounds`, cheapest S first: for S level i and R level j, the scale
/// of level (i + j) mod 3 (see the module documentation).
pub fn candidates(bounds: &Bounds) -> Vec<Quality> {
    let mut out: Vec<Quality> = Vec::new();
    for (i, &spp) in SPP.iter().enumerate() {
        for (j, &depth) in DEPTH.iter().enumerate() {
            let q = bounds.clamp(Quality {
                spp,
                depth,
                scale: SCALE[(i + j) % SCALE.len()],
            });
            if !out.contains(&q) {
                out.push(q);
            }
        }
    }
    out
}

/// The index of the candidate with the lowest displayed FLIP (the first of equals); a
/// candidate without a score (no sample on screen) never wins. `None` when none has one.
pub fn lowest_flip(flips: &[Option<f64>]) -> Option<usize> {
    flips
        .iter()
        .enumerate()
        .filter_map(|(i, flip)| flip.map(|f| (i, f)))
        .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)))
        .map(|(i, _)| i)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nine_candidates_try_every_level_three_times_and_every_pair_once() {
        let all = candidates(&Bounds::default());
        assert_eq!(all.len(), 9);
        for q in &all {
            assert_eq!(all.iter().filter(|o| o.spp == q.spp).count(), 3);
            assert_eq!(all.iter().filter(|o| o.depth == q.depth).count(), 3);
            assert_eq!(all.iter().filter(|o| o.scale == q.scale).count(), 3);
            let pairs = all
                .iter()
                .filter(|o| (o.depth, o.scale) == (q.depth, q.scale))
                .count();
            assert_eq!(pairs, 1, "{q}");
        }
        assert!(all.contains(&Quality::new(1.0, 16, 1.0)), "the paper's");
        assert!(all.contains(&Quality::new(1.0, 2, 0.5)), "the cheapest");
    }

    #[test]
    fn candidates_keep_to_the_bounds() {
        let bounds = Bounds {
            depth_max: 4,
            scale_min: 0.75,
            ..Bounds::default()
        };
        let all = candidates(&bounds);
        assert!(all.iter().all(|q| q.depth <= 4 && q.scale >= 0.75));
        assert!(all.len() < 9, "clamped duplicates are dropped: {all:?}");
        assert!(all.iter().enumerate().all(|(i, q)| !all[..i].contains(q)));
    }

    #[test]
    fn the_lowest_displayed_flip_wins() {
        assert_eq!(
            lowest_flip(&[Some(0.2), Some(0.05), None, Some(0.1)]),
            Some(1)
        );
        assert_eq!(lowest_flip(&[None, Some(0.3), Some(0.3)]), Some(1));
        assert_eq!(lowest_flip(&[None, None]), None);
        assert_eq!(lowest_flip(&[]), None);
    }
}
