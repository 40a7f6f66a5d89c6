//! The suite's table: for each method and scene the score's median and range over the
//! runs, the method's rank on that scene, and its mean rank over the scenes.

use crate::cell::CellResult;
use crate::error::SuiteError;
use serde::Serialize;
use std::collections::BTreeMap;

/// What the table ranks by.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Metric {
    /// ColorVideoVDP's JOD (higher is better), when every cell has one.
    Jod,
    /// Displayed FLIP (lower is better), otherwise.
    DisplayedFlip,
}

impl Metric {
    /// The name the table prints.
    pub fn name(self) -> &'static str {
        match self {
            Metric::Jod => "JOD (higher is better)",
            Metric::DisplayedFlip => "displayed FLIP (lower is better)",
        }
    }

    fn score(self, r: &CellResult) -> f64 {
        match self {
            Metric::Jod => r.jod.unwrap_or(f64::NAN),
            Metric::DisplayedFlip => r.displayed_flip,
        }
    }

    /// Whether score `a` is better than `b`.
    fn better(self, a: f64, b: f64) -> bool {
        match self {
            Metric::Jod => a > b,
            Metric::DisplayedFlip => a < b,
        }
    }
}

/// One method on one scene.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Entry {
    /// Runs scored.
    pub runs: usize,
    /// The median score.
    pub median: f64,
    /// The lowest and highest score.
    pub range: [f64; 2],
    /// Frames shown per second, median.
    pub displayed_fps: f64,
    /// The method's rank on the scene (1 = best; ties share the mean of their ranks).
    pub rank: f64,
}

/// One method's row.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Row {
    /// The method.
    pub method: String,
    /// Its entry on each scene (in the table's scene order), None where it has no result.
    pub scenes: Vec<Option<Entry>>,
    /// Its mean rank over the scenes where it has a result.
    pub mean_rank: f64,
    /// Scenes where it ranked first.
    pub wins: usize,
}

/// The table.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Table {
    /// What the scores are.
    pub metric: Metric,
    /// The scenes, in column order.
    pub scenes: Vec<String>,
    /// The methods' rows, in the order asked for.
    pub rows: Vec<Row>,
    /// Seconds all the cells took together.
    pub cell_seconds: f64,
    /// Cells in the table.
    pub cells: usize,
}

impl Table {
    /// Joins `results`, with the scenes and methods in the orders given (names missing there
    /// follow in alphabetical order).
    pub fn new(
        results: &[CellResult],
        scene_order: &[String],
        method_order: &[String],
    ) -> Result<Self, SuiteError> {
        if results.is_empty() {
            return Err(SuiteError::NoResults("the folders given".into()));
        }
        let metric = if results.iter().all(|r| r.jod.is_some()) {
            Metric::Jod
        } else {
            Metric::DisplayedFlip
        };
        let scenes = ordered(results.iter().map(|r| &r.cell.scene), scene_order);
        let methods = ordered(results.iter().map(|r| &r.cell.method), method_order);
        let mut groups: BTreeMap<(&str, &str), Vec<&CellResult>> = BTreeMap::new();
        for r in results {
            groups
                .entry((r.cell.method.as_str(), r.cell.scene.as_str()))
                .or_default()
                .push(r);
        }
        let mut grid: Vec<Vec<Option<Entry>>> = methods
            .iter()
            .map(|m| {
                scenes
                    .iter()
                    .map(|s| {
                        groups
                            .get(&(m.as_str(), s.as_str()))
                            .map(|g| entry(metric, g))
                    })
                    .collect()
            })
            .collect();
        for column in 0..scenes.len() {
            rank_column(metric, &mut grid, column);
        }
        let rows = methods
            .into_iter()
            .zip(grid)
            .map(|(method, entries)| row(method, entries))
            .collect();
        Ok(Self {
            metric,
            scenes,
            rows,
            cell_seconds: results.iter().map(|r| r.seconds).sum(),
            cells: results.len(),
        })
    }

    /// The table in Markdown: a column per scene (median, range and rank), the mean rank.
    pub fn to_markdown(&self) -> String {
        let mut out = format!(
            "Scores: {} — median (lowest–highest) over the runs, #rank on the scene.\n\n",
            self.metric.name()
        );
        out += &format!(
            "| method | {} | mean rank | wins |\n",
            self.scenes.join(" | ")
        );
        out += &format!("|---|{}---|---|\n", "---|".repeat(self.scenes.len()));
        let digits = match self.metric {
            Metric::Jod => 2,
            Metric::DisplayedFlip => 4,
        };
        for row in &self.rows {
            let cells: Vec<String> = row
                .scenes
                .iter()
                .map(|e| match e {
                    Some(e) => format!(
                        "{:.d$} ({:.d$}–{:.d$}) #{}",
                        e.median,
                        e.range[0],
                        e.range[1],
                        e.rank,
                        d = digits
                    ),
                    None => "-".to_string(),
                })
                .collect();
            out += &format!(
                "| {} | {} | {:.2} | {} |\n",
                row.method,
                cells.join(" | "),
                row.mean_rank,
                row.wins
            );
        }
        out += &format!(
            "\n{} cells, {:.0} s of running time in all.\n",
            self.cells, self.cell_seconds
        );
        out
    }
}

/// The names in `wanted` order first, then the others alphabetically.
fn ordered<'a>(names: impl Iterator<Item = &'a String>, wanted: &[String]) -> Vec<String> {
    let mut seen: Vec<String> = names.cloned().collect();
    seen.sort();
    seen.dedup();
    let mut out: Vec<String> = wanted
        .iter()
        .filter(|w| seen.contains(w))
        .cloned()
        .collect();
    out.extend(seen.into_iter().filter(|s| !wanted.contains(s)));
    out
}

fn entry(metric: Metric, group: &[&CellResult]) -> Entry {
    let mut scores: Vec<f64> = group.iter().map(|r| metric.score(r)).collect();
    scores.sort_by(f64::total_cmp);
    let mut fps: Vec<f64> = group.iter().map(|r| r.displayed_fps).collect();
    fps.sort_by(f64::total_cmp);
    Entry {
        runs: scores.len(),
        median: median(&scores),
        range: [scores[0], scores[scores.len() - 1]],
        displayed_fps: median(&fps),
        rank: 0.0,
    }
}

/// The median of sorted, non-empty `values`.
fn median(values: &[f64]) -> f64 {
    let n = values.len();
    if n % 2 == 1 {
        values[n / 2]
    } else {
        0.5 * (values[n / 2 - 1] + values[n / 2])
    }
}

/// Ranks the entries of one scene by median: 1 for the best; ties share their mean rank.
fn rank_column(metric: Metric, grid: &mut [Vec<Option<Entry>>], column: usize) {
    let medians: Vec<(usize, f64)> = grid
        .iter()
        .enumerate()
        .filter_map(|(row, entries)| entries[column].as_ref().map(|e| (row, e.median)))
        .collect();
    for &(row, m) in &medians {
        let better = medians.iter().filter(|(_, o)| metric.better(*o, m)).count();
        let tied = medians.iter().filter(|(_, o)| *o == m).count();
        if let Some(e) = grid[row][column].as_mut() {
            e.rank = better as f64 + (1.0 + tied as f64) / 2.0;
        }
    }
}

fn row(method: String, scenes: Vec<Option<Entry>>) -> Row {
    let ranks: Vec<f64> = scenes.iter().flatten().map(|e| e.rank).collect();
    Row {
        method,
        mean_rank: ranks.iter().sum::<f64>() / ranks.len().max(1) as f64,
        wins: ranks.iter().filter(|&&r| r == 1.0).count(),
        scenes,
    }
}
