//! The paper's Figure 4 for every controller: frame time against frame with the band shaded,
//! and the quality parameters below it; with `--quality`, a third row per controller shows
//! the measured frames' FLIP against the reference. And the subjective experiment's figure:
//! JOD against the frames shown per second, a point per method ([`write_jod_plot`]).
//!
//! Frame axes are labelled in whole numbers, and legends sit beside the data, never on it.

use super::record::ControllerRun;
use anyhow::{Result, anyhow};
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
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
/// The width of the legend column beside a chart.
const LEGEND_WIDTH: u32 = 170;

/// Registers the embedded font (once per process).
pub(crate) fn register_plot_font() {
    static FONT_ONCE: Once = Once::new();
    FONT_ONCE.call_once(|| {
        register_font("sans-serif", FontStyle::Normal, FONT)
            .unwrap_or_else(|_| panic!("the embedded DejaVuSans.ttf is a valid font"));
    });
}

/// An axis label: whole numbers without decimals, others with up to two.
fn tick(v: &f64) -> String {
    let text = format!("{v:.2}");
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// A frame axis label: a whole number.
fn frame_tick(v: &f64) -> String {
    format!("{v:.0}")
}

/// How a series is drawn in a legend and on a chart.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Marker {
    Line,
    Circle,
    Square,
    Triangle,
    Cross,
    /// The hollow forms, for a method's runs with the temporal mode.
    Ring,
    HollowTriangle,
    CircledCross,
}

impl Marker {
    /// The hollow form of a method's marker.
    fn hollow(self) -> Self {
        match self {
            Marker::Circle => Marker::Ring,
            Marker::Triangle => Marker::HollowTriangle,
            Marker::Cross => Marker::CircledCross,
            other => other,
        }
    }
}

/// Draws `marker` at each of `points` (chart coordinates) on `chart`.
fn draw_markers<DB: DrawingBackend>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    marker: Marker,
    colour: RGBColor,
    points: &[(f64, f64)],
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let style = colour.filled();
    let at = points.iter().copied();
    match marker {
        Marker::Line => chart.draw_series(LineSeries::new(at, colour.stroke_width(2))),
        Marker::Circle => chart.draw_series(at.map(|p| Circle::new(p, 5, style))),
        Marker::Triangle => chart.draw_series(at.map(|p| TriangleMarker::new(p, 6, style))),
        Marker::Cross => chart.draw_series(at.map(|p| Cross::new(p, 5, colour.stroke_width(2)))),
        Marker::Square => chart.draw_series(
            at.map(|p| EmptyElement::at(p) + Rectangle::new([(-4, -4), (4, 4)], style)),
        ),
        Marker::Ring => chart.draw_series(at.map(|p| Circle::new(p, 5, colour.stroke_width(2)))),
        Marker::HollowTriangle => chart.draw_series(at.map(|p| {
            EmptyElement::at(p)
                + PathElement::new([(0, -7), (6, 4), (-6, 4), (0, -7)], colour.stroke_width(2))
        })),
        Marker::CircledCross => chart.draw_series(at.map(|p| {
            EmptyElement::at(p)
                + Cross::new((0, 0), 4, colour.stroke_width(2))
                + Circle::new((0, 0), 7, colour.stroke_width(1))
        })),
    }
    .map_err(plot_err)?;
    Ok(())
}

/// Draws a legend (a marker or a line per entry, then its label) in `area`, beside the data.
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[(String, RGBColor, Marker)],
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let text = TextStyle::from(("sans-serif", 13).into_font()).color(&BLACK);
    for (i, (label, colour, marker)) in entries.iter().enumerate() {
        let (x, y) = (14, 16 + 18 * i as i32);
        let style = colour.filled();
        match marker {
            Marker::Line => area.draw(&PathElement::new(
                [(x - 9, y), (x + 9, y)],
                colour.stroke_width(2),
            )),
            Marker::Circle => area.draw(&Circle::new((x, y), 5, style)),
            Marker::Triangle => area.draw(&TriangleMarker::new((x, y), 6, style)),
            Marker::Cross => area.draw(&Cross::new((x, y), 5, colour.stroke_width(2))),
            Marker::Square => area.draw(&Rectangle::new([(x - 4, y - 4), (x + 4, y + 4)], style)),
            Marker::Ring => area.draw(&Circle::new((x, y), 5, colour.stroke_width(2))),
            Marker::HollowTriangle => area.draw(&PathElement::new(
                [(x, y - 7), (x + 6, y + 4), (x - 6, y + 4), (x, y - 7)],
                colour.stroke_width(2),
            )),
            Marker::CircledCross => area
                .draw(&Cross::new((x, y), 4, colour.stroke_width(2)))
                .and_then(|_| area.draw(&Circle::new((x, y), 7, colour.stroke_width(1)))),
        }
        .map_err(plot_err)?;
        area.draw(&Text::new(label.clone(), (x + 16, y - 7), text.clone()))
            .map_err(plot_err)?;
    }
    Ok(())
}

/// Writes the figure as PNG and SVG.
pub fn write_plots(runs: &[ControllerRun], band: (f64, f64), png: &Path, svg: &Path) -> Result<()> {
    register_plot_font();
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
        let (charts, legend) = area.split_horizontally(PANEL_WIDTH - LEGEND_WIDTH);
        let (top, rest) = charts.split_vertically(TIME_HEIGHT);
        draw_time(&top, run, band, t_max)?;
        if has_flip(runs) {
            let (middle, bottom) = rest.split_vertically(QUALITY_HEIGHT);
            draw_quality(&middle, run, q_max)?;
            draw_flip(&bottom, run, flip_max)?;
        } else {
            draw_quality(&rest, run, q_max)?;
        }
        let (_, quality_legend) = legend.split_vertically(TIME_HEIGHT);
        draw_legend(
            &quality_legend,
            &[
                ("R (depth)".into(), DEPTH_COLOUR, Marker::Line),
                ("S (rays/pixel)".into(), SPP_COLOUR, Marker::Line),
                ("scale (right axis)".into(), SCALE_COLOUR, Marker::Line),
            ],
        )?;
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
        .x_label_formatter(&frame_tick)
        .y_label_formatter(&tick)
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
        .x_label_formatter(&frame_tick)
        .y_label_formatter(&tick)
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(plot_err)?;
    chart
        .configure_secondary_axes()
        .y_desc("scale")
        .y_label_formatter(&tick)
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
        .map_err(plot_err)?;
    chart
        .draw_series(series(SPP_COLOUR, |f| f.spp as f64))
        .map_err(plot_err)?;
    chart
        .draw_secondary_series(series(SCALE_COLOUR, |f| f.scale as f64))
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
        .x_label_formatter(&frame_tick)
        .y_label_formatter(&tick)
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

/// Colours of the benches' bands on the JOD plot, in order of appearance.
const BAND_COLOURS: [RGBColor; 4] = [
    RGBColor(20, 60, 160),
    RGBColor(200, 60, 30),
    RGBColor(30, 140, 60),
    RGBColor(120, 60, 160),
];
/// The colour of the fixed qualities (the same for every band: no control).
const FIXED_COLOUR: RGBColor = RGBColor(110, 110, 110);
/// Markers of the controllers, in order of appearance.
/// The controllers' markers (squares are the fixed qualities').
const METHOD_MARKERS: [Marker; 3] = [Marker::Circle, Marker::Triangle, Marker::Cross];

/// A run's method without its temporal mode, and whether it ran with it.
fn method_of(name: &str) -> (&str, bool) {
    match name.strip_suffix(" +temporal") {
        Some(base) => (base, true),
        None => (name, false),
    }
}

/// Whether a run is a fixed quality: the paper's baseline or any other `fixed`, the
/// most-in-band or the best-looking fixed quality (or the most-in-band one under its old
/// name, "best fixed", in summaries written before it was renamed).
fn is_fixed(name: &str) -> bool {
    [
        "fixed",
        "most-in-band fixed",
        "best-looking fixed",
        "best fixed",
    ]
    .iter()
    .any(|prefix| name.starts_with(prefix))
}

/// One method on the JOD plot.
#[derive(Clone, Debug, PartialEq)]
pub struct JodPoint {
    /// The controller's name in the summary.
    pub name: String,
    /// The bench's band, ms.
    pub band_ms: [f64; 2],
    /// Frames shown per second, on average.
    pub displayed_fps: f64,
    /// The run's JOD score.
    pub jod: f64,
}

/// JOD against mean displayed frames per second, a point per method: each controller a
/// marker, each bench's band a colour, the fixed qualities joined by a grey line (PNG and an
/// SVG beside it).
pub fn write_jod_plot(points: &[JodPoint], png: &Path) -> Result<()> {
    register_plot_font();
    let svg = png.with_extension("svg");
    let size = (1100, 620);
    {
        let root = BitMapBackend::new(png, size).into_drawing_area();
        draw_jod(&root, points)?;
        root.present()
            .map_err(|e| anyhow!("cannot write {}: {e}", png.display()))?;
    }
    let root = SVGBackend::new(&svg, size).into_drawing_area();
    draw_jod(&root, points)?;
    root.present()
        .map_err(|e| anyhow!("cannot write {}: {e}", svg.display()))?;
    Ok(())
}

fn draw_jod<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, points: &[JodPoint]) -> Result<()>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(plot_err)?;
    let (chart_area, legend) = root.split_horizontally(root.dim_in_pixel().0 - 260);
    let (fps_lo, fps_hi) = points.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| {
        (lo.min(p.displayed_fps), hi.max(p.displayed_fps))
    });
    let (jod_lo, jod_hi) = points.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| {
        (lo.min(p.jod), hi.max(p.jod))
    });
    let mut chart = ChartBuilder::on(&chart_area)
        .caption(
            "Perceived quality against frames shown per second",
            ("sans-serif", 20),
        )
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(55)
        .build_cartesian_2d(
            (fps_lo - 2.0).floor()..(fps_hi + 2.0).ceil(),
            (jod_lo - 0.1)..(jod_hi + 0.1),
        )
        .map_err(plot_err)?;
    chart
        .configure_mesh()
        .x_desc("mean displayed frames per second")
        .y_desc("JOD (ColorVideoVDP; 10 = the reference)")
        .x_label_formatter(&frame_tick)
        .y_label_formatter(&tick)
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(plot_err)?;

    let mut fixed: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| is_fixed(&p.name))
        .map(|p| (p.displayed_fps, p.jod))
        .collect();
    fixed.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut entries = Vec::new();
    if !fixed.is_empty() {
        draw_markers(&mut chart, Marker::Line, FIXED_COLOUR, &fixed)?;
        draw_markers(&mut chart, Marker::Square, FIXED_COLOUR, &fixed)?;
        entries.push(("fixed qualities".to_string(), FIXED_COLOUR, Marker::Square));
    }
    let mut bands: Vec<[f64; 2]> = Vec::new();
    let mut methods: Vec<&str> = Vec::new();
    let mut any_temporal = false;
    for p in points.iter().filter(|p| !is_fixed(&p.name)) {
        if !bands.contains(&p.band_ms) {
            bands.push(p.band_ms);
        }
        let (base, temporal) = method_of(&p.name);
        any_temporal |= temporal;
        if !methods.contains(&base) {
            methods.push(base);
        }
    }
    for p in points.iter().filter(|p| !is_fixed(&p.name)) {
        let (base, temporal) = method_of(&p.name);
        let b = bands
            .iter()
            .position(|band| *band == p.band_ms)
            .unwrap_or(0);
        let m = methods.iter().position(|name| *name == base).unwrap_or(0);
        let marker = METHOD_MARKERS[m % METHOD_MARKERS.len()];
        draw_markers(
            &mut chart,
            if temporal { marker.hollow() } else { marker },
            BAND_COLOURS[b % BAND_COLOURS.len()],
            &[(p.displayed_fps, p.jod)],
        )?;
    }
    for (b, band) in bands.iter().enumerate() {
        entries.push((
            format!("band [{}, {}] ms", tick(&band[0]), tick(&band[1])),
            BAND_COLOURS[b % BAND_COLOURS.len()],
            Marker::Line,
        ));
    }
    for (m, method) in methods.iter().enumerate() {
        entries.push((
            method.to_string(),
            BLACK,
            METHOD_MARKERS[m % METHOD_MARKERS.len()],
        ));
    }
    if any_temporal {
        entries.push((
            "hollow: with the temporal mode".to_string(),
            BLACK,
            Marker::Ring,
        ));
    }
    let (_, legend) = legend.split_vertically(50);
    draw_legend(&legend, &entries)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fixed_qualities_under_every_name_are_fixed() {
        for name in [
            "fixed S=1 R=16",
            "most-in-band fixed S=2 R=5",
            "best-looking fixed S=1 R=16 x0.75 +temporal",
            "best fixed S=4 R=0 x0.5",
        ] {
            assert!(is_fixed(name), "{name}");
        }
        for name in ["predictive", "step:knob=both", "perceptual +temporal +warp"] {
            assert!(!is_fixed(name), "{name}");
        }
    }
}
