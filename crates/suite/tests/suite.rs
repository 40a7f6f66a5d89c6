//! The suite's bookkeeping on a runner that computes its scores from the cell: cells run
//! once, a killed run resumes where it stopped, shards split the work and their results
//! join into one table whose ranks follow the scores.

use std::collections::HashMap;
use std::path::Path;
use steadyray_suite::run::CellEvent;
use steadyray_suite::{Cell, CellResult, CellRunner, Metric, Plan, Shard, Table, run_cells, store};
use tempfile::TempDir;

/// Scores each method by its position in the plan (the first method best), slightly
/// different per run; fails on `fail_on` (a cell id) once; counts the cells it ran.
#[derive(Default)]
struct Scorer {
    ran: HashMap<String, usize>,
    fail_on: Option<String>,
    jod: bool,
}

impl CellRunner for Scorer {
    fn run(&mut self, plan: &Plan, cell: &Cell, dir: &Path) -> Result<CellResult, String> {
        if self.fail_on.as_deref() == Some(&cell.id()) {
            self.fail_on = None;
            std::fs::write(dir.join("half-written.csv"), "frame\n").unwrap();
            return Err("the renderer failed".into());
        }
        assert!(
            std::fs::read_dir(dir).unwrap().next().is_none(),
            "the cell's folder is empty"
        );
        std::fs::write(dir.join("summary.json"), "{}").unwrap();
        *self.ran.entry(cell.id()).or_default() += 1;
        let position = plan
            .methods
            .iter()
            .position(|m| m.name == cell.method)
            .unwrap();
        let score = 9.0 - position as f64 * 0.1 + f64::from(cell.run) * 0.01;
        Ok(CellResult {
            cell: cell.clone(),
            displayed_flip: 0.01 * (1.0 + position as f64),
            jod: self.jod.then_some(score),
            displayed_fps: 60.0,
            in_band_pct: 95.0,
            seconds: 0.0,
        })
    }
}

/// A fresh temporary folder for one run's cells, removed when dropped.
fn folder(name: &str) -> TempDir {
    tempfile::Builder::new()
        .prefix(&format!("steadyray-suite-{name}-"))
        .tempdir()
        .unwrap()
}

fn small_plan() -> Plan {
    Plan::standard(2)
        .unwrap()
        .only_scenes(&["corridor".into(), "glass".into()])
        .unwrap()
        .only_methods(&["paper".into(), "refresh".into(), "refresh2+history".into()])
        .unwrap()
}

fn quiet(_: &Cell, _: usize, _: usize, _: &CellEvent) {}

#[test]
fn a_killed_run_resumes_and_finished_cells_are_not_redone() {
    let tmp = folder("resume");
    let root = tmp.path();
    let plan = small_plan();
    let mut runner = Scorer {
        fail_on: Some("glass/refresh/run-0".into()),
        jod: true,
        ..Scorer::default()
    };
    let err = run_cells(&plan, Shard::ALL, root, &mut runner, &mut quiet).unwrap_err();
    assert!(
        err.to_string()
            .contains("glass/refresh/run-0: the renderer failed"),
        "{err}"
    );
    let done_before = store::read_all(root).unwrap().len();
    assert_eq!(done_before, 4, "the cells before the failure are kept");

    let report = run_cells(&plan, Shard::ALL, root, &mut runner, &mut quiet).unwrap();
    assert_eq!(report.already_done, 4);
    assert_eq!(report.ran.len(), plan.cells().len() - 4);
    assert!(
        runner.ran.values().all(|&n| n == 1),
        "every cell ran once: {:?}",
        runner.ran
    );
    assert!(
        !store::cell_dir(root, &report.ran[0])
            .join("half-written.csv")
            .exists(),
        "the failed cell's leftovers are cleared"
    );
    let again = run_cells(&plan, Shard::ALL, root, &mut runner, &mut quiet).unwrap();
    assert!(again.ran.is_empty());
}

#[test]
fn shards_split_the_cells_and_their_results_join_into_one_table() {
    let plan = small_plan();
    let roots: Vec<TempDir> = (1..=3).map(|i| folder(&format!("shard-{i}"))).collect();
    let mut results = Vec::new();
    for (i, root) in roots.iter().map(TempDir::path).enumerate() {
        let mut runner = Scorer {
            jod: true,
            ..Scorer::default()
        };
        let shard = Shard::new(i as u32 + 1, 3).unwrap();
        run_cells(&plan, shard, root, &mut runner, &mut quiet).unwrap();
        results.extend(store::read_all(root).unwrap());
    }
    assert_eq!(results.len(), plan.cells().len());
    let scenes: Vec<String> = plan.scenes.iter().map(|s| s.name.clone()).collect();
    let methods: Vec<String> = plan.methods.iter().map(|m| m.name.clone()).collect();
    let table = Table::new(&results, &scenes, &methods).unwrap();
    assert_eq!(table.metric, Metric::Jod);
    assert_eq!(table.scenes, scenes);
    let ranks: Vec<f64> = table.rows.iter().map(|r| r.mean_rank).collect();
    assert_eq!(ranks, [1.0, 2.0, 3.0]);
    let paper = &table.rows[0].scenes[0].as_ref().unwrap();
    assert_eq!((paper.runs, paper.range), (2, [9.0, 9.01]));
    assert!((paper.median - 9.005).abs() < 1e-12);
    let markdown = table.to_markdown();
    assert!(
        markdown.contains("| paper | 9.00 (9.00–9.01) #1 | 9.00 (9.00–9.01) #1 | 1.00 | 2 |"),
        "{markdown}"
    );
}

#[test]
fn without_jod_everywhere_the_table_ranks_by_displayed_flip() {
    let tmp = folder("flip");
    let root = tmp.path();
    let plan = small_plan();
    let mut runner = Scorer::default();
    run_cells(&plan, Shard::ALL, root, &mut runner, &mut quiet).unwrap();
    let results = store::read_all(root).unwrap();
    let table = Table::new(&results, &[], &[]).unwrap();
    assert_eq!(table.metric, Metric::DisplayedFlip);
    let best = table.rows.iter().find(|r| r.mean_rank == 1.0).unwrap();
    assert_eq!(best.method, "paper", "the lowest FLIP ranks first");
}

#[test]
fn a_result_file_of_another_cell_is_refused() {
    let tmp = folder("mismatch");
    let root = tmp.path();
    let plan = small_plan();
    let cells = plan.cells();
    let dir = store::fresh_cell_dir(root, &cells[0]).unwrap();
    let wrong = CellResult {
        cell: cells[1].clone(),
        displayed_flip: 0.1,
        jod: None,
        displayed_fps: 60.0,
        in_band_pct: 90.0,
        seconds: 1.0,
    };
    std::fs::write(
        dir.join(store::RESULT_FILE),
        serde_json::to_string(&wrong).unwrap(),
    )
    .unwrap();
    let err = store::finished(root, &cells[0]).unwrap_err().to_string();
    assert!(err.contains("it is the result of"), "{err}");
}
