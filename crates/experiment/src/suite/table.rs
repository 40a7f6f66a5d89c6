//! `suite table`: joins the finished cells of one or more suite folders (shards run on
//! several machines) into one table, `table.md` and `table.json`, and its plot.

use super::plot::write_suite_plot;
use anyhow::{Context, Result, bail};
use std::path::{Path, PathBuf};
use steadyray_suite::method::standard_methods;
use steadyray_suite::scene::standard_scenes;
use steadyray_suite::{Table, store};

/// Reads every finished cell under `folders`, writes `table.md`, `table.json`, `suite.png`
/// and `suite.svg` into `out`, and returns the table's Markdown.
pub fn write_table(folders: &[PathBuf], out: &Path) -> Result<String> {
    let mut results = Vec::new();
    for folder in folders {
        results.extend(store::read_all(folder).with_context(|| folder.display().to_string())?);
    }
    if results.is_empty() {
        bail!(
            "no finished cell under {}: run `steadyray suite run` first",
            folders
                .iter()
                .map(|f| f.display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    let scenes: Vec<String> = standard_scenes().into_iter().map(|s| s.name).collect();
    let methods: Vec<String> = standard_methods().into_iter().map(|m| m.name).collect();
    let table = Table::new(&results, &scenes, &methods)?;
    std::fs::create_dir_all(out).with_context(|| out.display().to_string())?;
    let markdown = table.to_markdown();
    write(&out.join("table.md"), &markdown)?;
    write(
        &out.join("table.json"),
        &serde_json::to_string_pretty(&table)?,
    )?;
    write_suite_plot(&table, &out.join("suite.png"), &out.join("suite.svg"))?;
    Ok(markdown)
}

fn write(path: &Path, text: &str) -> Result<()> {
    std::fs::write(path, text).with_context(|| format!("cannot write {}", path.display()))
}
