//! The paper's Figure 4 for every controller: frame time against frame with the band shaded,
//! and the quality parameters below it; with `--quality`, a third row per controller shows
//! the measured frames' FLIP against the reference.

use super::record::ControllerRun;
use anyhow::{Result, anyhow};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};
use std::path::Path;
use std::sync::Once;

const PANEL_WIDTH: u32 = 1400;
const TIME_HEIGHT: u32 = 230;
const QUALITY_HEIGHT: u32 = 130;
const FLIP_HEIGHT: u32 = 110;
const FLIP_COLOUR: RGBColor = RGBColor(180, 40, 120);
const FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");
const BAND_COLOUR: RGBColor = RGBColor(200, 230, 200);
const TP_COLOUR: RGBColor = RGBColor(20, 60, 160);
const DEPTH_COLOUR: RGBColor = RGBColor(200, 60, 30);
const SPP_COLOUR: RGBColor = RGBColor(30, 140, 60);
const SCALE_COLOUR: RGBColor = RGBColor(120, 60, 160);

/// Writes the figure as PNG and SVG.
pub fn write_plots(runs: &[ControllerRun], band: (f64, f64), png: &Path, svg: &Path) -> Result<()> {
    static FONT_ONCE: Once = Once::new();
    FONT_ONCE.call_once(|| {
        register_font("sans-serif", FontStyle::Normal, FONT)
            .unwrap_or_else(|_| panic!("the embedded DejaVuSans.ttf is a valid font"));
    });
    let height = panel_height(runs) * runs.len().max(1) as u32;
    {
        let root = BitMapBackend::new(png, (PANEL_WIDTH, height)).into_drawing_area();
        draw(&root, runs, band)?;
        root.present()
            .map_err(|e| anyhow!("cannot write {}: {e}", png.display()))?;
    }
    let root = SVGBackend::new(svg, (PANEL_WIDTH, height)).into_drawing_area();
    draw(&root, runs, band)?;
    root.present()
        .map_err(|e| anyhow!("cannot write {}: {e}", svg.display()))?;
    Ok(())
}

/// Whether any run measured FLIP (then every panel gets a FLIP row).
fn has_flip(runs: &[ControllerRun]) -> bool {
    runs.iter().any(|r| r.flip.is_some())
}

/// The height of one controller's panel.
fn panel_height(runs: &[ControllerRun]) -> u32 {
    TIME_HEIGHT + QUALITY_HEIGHT + if has_flip(runs) { FLIP_HEIGHT } else { 0 }
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    runs: &[ControllerRun],
    band: (f64, f64),
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(plot_err)?;
    let t_max = runs
        .iter()
        .flat_map(|r| r.rows.iter().map(|f| f.tp_ms))
        .fold(band.1 * 1.5, f64::max)
        .min(band.1 * 4.0);
    let depth_max = runs
        .iter()
        .flat_map(|r| r.rows.iter().map(|f| f.depth))
        .max()
        .unwrap_or(1)
        .max(1) as f64;
    let spp_max = runs
        .iter()
        .flat_map(|r| r.rows.iter().map(|f| f.spp as f64))
        .fold(1.0, f64::max);
    let q_max = depth_max.max(spp_max) * 1.1;
    let flip_max = runs
        .iter()
        .flat_map(|r| r.rows.iter().filter_map(|f| f.flip))
        .fold(0.05, f64::max)
        * 1.1;
    for (run, area) in runs.iter().zip(root.split_evenly((runs.len().max(1), 1))) {
        let (top, rest) = area.split_vertically(TIME_HEIGHT);
        draw_time(&top, run, band, t_max)?;
        if has_flip(runs) {
            let (middle, bottom) = rest.split_vertically(QUALITY_HEIGHT);
            draw_quality(&middle, run, q_max)?;
            draw_flip(&bottom, run, flip_max)?;
        } else {
            draw_quality(&rest, run, q_max)?;
        }
    }
    Ok(())
}

fn draw_time<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    run: &ControllerRun,
    band: (f64, f64),
    t_max: f64,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let frames = run.rows.len().max(1) as f64;
    let caption = format!(
        "{}: {:.1} % of frames in [{}, {}] ms",
        run.name, run.summary.in_band_pct, band.0, band.1
    );
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", 18))
        .margin(6)
        .x_label_area_size(22)
        .y_label_area_size(50)
        .build_cartesian_2d(0.0..frames, 0.0..t_max)
        .map_err(plot_err)?;
    chart
        .configure_mesh()
        .y_desc("Tp (ms)")
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(plot_err)?;
    chart
        .draw_series(std::iter::once(Rectangle::new(
            [(0.0, band.0), (frames, band.1)],
            BAND_COLOUR.filled(),
        )))
        .map_err(plot_err)?;
    chart
        .draw_series(LineSeries::new(
            run.rows
                .iter()
                .enumerate()
                .map(|(i, f)| (i as f64, f.tp_ms.min(t_max))),
            TP_COLOUR.stroke_width(1),
        ))
        .map_err(plot_err)?;
    Ok(())
}

fn draw_quality<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    run: &ControllerRun,
    q_max: f64,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let frames = run.rows.len().max(1) as f64;
    let mut chart = ChartBuilder::on(area)
        .margin(6)
        .x_label_area_size(22)
        .y_label_area_size(50)
        .right_y_label_area_size(50)
        .build_cartesian_2d(0.0..frames, 0.0..q_max)
        .map_err(plot_err)?
        .set_secondary_coord(0.0..frames, 0.0..1.05);
    chart
        .configure_mesh()
        .y_desc("R, S")
        .x_desc("frame")
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(plot_err)?;
    chart
        .configure_secondary_axes()
        .y_desc("scale")
        .draw()
        .map_err(plot_err)?;
    let series = |colour: RGBColor, value: fn(&super::record::FrameRow) -> f64| {
        LineSeries::new(
            run.rows
                .iter()
                .enumerate()
                .map(move |(i, f)| (i as f64, value(f))),
            colour.stroke_width(2),
        )
    };
    chart
        .draw_series(series(DEPTH_COLOUR, |f| f.depth as f64))
        .map_err(plot_err)?
        .label("R (depth)")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 16, y)], DEPTH_COLOUR));
    chart
        .draw_series(series(SPP_COLOUR, |f| f.spp as f64))
        .map_err(plot_err)?
        .label("S (rays/pixel)")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 16, y)], SPP_COLOUR));
    chart
        .draw_secondary_series(series(SCALE_COLOUR, |f| f.scale as f64))
        .map_err(plot_err)?
        .label("scale (right axis)")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 16, y)], SCALE_COLOUR));
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(plot_err)?;
    Ok(())
}

/// FLIP of the measured frames against frame, with the run's mean in the caption.
fn draw_flip<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    run: &ControllerRun,
    flip_max: f64,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let frames = run.rows.len().max(1) as f64;
    let caption = run.flip.map_or_else(
        || "FLIP: not measured".to_string(),
        |(mean, p95)| format!("FLIP vs reference: mean {mean:.4}, p95 {p95:.4} (lower is better)"),
    );
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", 14))
        .margin(6)
        .x_label_area_size(22)
        .y_label_area_size(50)
        .right_y_label_area_size(50)
        .build_cartesian_2d(0.0..frames, 0.0..flip_max)
        .map_err(plot_err)?;
    chart
        .configure_mesh()
        .y_desc("FLIP")
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(plot_err)?;
    let points: Vec<(f64, f64)> = run
        .rows
        .iter()
        .enumerate()
        .filter_map(|(i, f)| f.flip.map(|v| (i as f64, v)))
        .collect();
    chart
        .draw_series(LineSeries::new(points.clone(), FLIP_COLOUR.stroke_width(1)))
        .map_err(plot_err)?;
    chart
        .draw_series(
            points
                .into_iter()
                .map(|p| Circle::new(p, 2, FLIP_COLOUR.filled())),
        )
        .map_err(plot_err)?;
    Ok(())
}

fn plot_err<E: std::error::Error + Send + Sync + 'static>(e: E) -> anyhow::Error {
    anyhow!("plotting failed: {e}")
}
