//! The suite's figure: each method's median score on each scene, with its range over the
//! runs, a colour per method; the legend gives each method's mean rank.

use crate::bench::plot::register_plot_font;
use anyhow::{Result, anyhow};
use plotters::prelude::*;
use std::path::Path;
use steadyray_suite::{Metric, Table};

const WIDTH: u32 = 1200;
const HEIGHT: u32 = 560;

/// Writes the figure of `table` as PNG and SVG.
pub fn write_suite_plot(table: &Table, png: &Path, svg: &Path) -> Result<()> {
    register_plot_font();
    draw(
        table,
        BitMapBackend::new(png, (WIDTH, HEIGHT)).into_drawing_area(),
    )?;
    draw(
        table,
        SVGBackend::new(svg, (WIDTH, HEIGHT)).into_drawing_area(),
    )
}

fn draw<DB: DrawingBackend>(
    table: &Table,
    area: DrawingArea<DB, plotters::coord::Shift>,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow!("drawing the suite plot: {e}");
    area.fill(&WHITE).map_err(err)?;
    let (chart_area, legend_area) = area.split_horizontally(WIDTH - 300);
    let entries = table.rows.iter().flat_map(|r| r.scenes.iter().flatten());
    let (lo, hi) = entries.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), e| {
        (lo.min(e.range[0]), hi.max(e.range[1]))
    });
    let pad = ((hi - lo) * 0.08).max(1e-3);
    let columns = table.scenes.len() as f64;
    let mut chart = ChartBuilder::on(&chart_area)
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(64)
        .build_cartesian_2d(-0.5..columns - 0.5, (lo - pad)..(hi + pad))
        .map_err(err)?;
    let scenes = table.scenes.clone();
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_labels(scenes.len())
        .x_label_formatter(&|x| {
            let i = x.round();
            if (x - i).abs() < 1e-6 && i >= 0.0 {
                scenes.get(i as usize).cloned().unwrap_or_default()
            } else {
                String::new()
            }
        })
        .y_desc(match table.metric {
            Metric::Jod => "JOD (higher is better)",
            Metric::DisplayedFlip => "displayed FLIP (lower is better)",
        })
        .draw()
        .map_err(err)?;
    let n = table.rows.len().max(1) as f64;
    for (i, row) in table.rows.iter().enumerate() {
        let colour = Palette99::pick(i).to_rgba();
        let offset = (i as f64 + 0.5) / n * 0.7 - 0.35;
        for (column, entry) in row.scenes.iter().enumerate() {
            let Some(e) = entry else { continue };
            let x = column as f64 + offset;
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(x, e.range[0]), (x, e.range[1])],
                    colour.stroke_width(2),
                )))
                .map_err(err)?;
            chart
                .draw_series(std::iter::once(Circle::new(
                    (x, e.median),
                    5,
                    colour.filled(),
                )))
                .map_err(err)?;
        }
    }
    draw_legend(table, &legend_area).map_err(err)
}

fn draw_legend<DB: DrawingBackend>(
    table: &Table,
    area: &DrawingArea<DB, plotters::coord::Shift>,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let style = TextStyle::from(("sans-serif", 14).into_font()).color(&BLACK);
    area.draw(&Text::new("method (mean rank)", (8, 16), style.clone()))?;
    for (i, row) in table.rows.iter().enumerate() {
        let y = 44 + 24 * i as i32;
        area.draw(&Circle::new(
            (14, y),
            5,
            Palette99::pick(i).to_rgba().filled(),
        ))?;
        let label = format!("{} ({:.2})", row.method, row.mean_rank);
        area.draw(&Text::new(label, (26, y - 8), style.clone()))?;
    }
    Ok(())
}
