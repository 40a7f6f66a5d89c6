//! The HUD: a frame-time graph with the band shaded, the current quality and throughput, and
//! the controls that retune the controller live. The controls edit a plain [`HudEdit`];
//! what changed comes out as [`HudChange`]s for the view to apply (testable without egui).

use super::history::{FrameHistory, HISTORY_S};
use egui::{Color32, Pos2, Rect, Sense, Shape, Stroke, vec2};
use steadyray_control::{Band, Bounds, CONTROLLER_NAMES, Quality};
use steadyray_render::MAX_DEPTH;

/// Seconds the HUD's in-band percentage and figures look back.
pub const FIGURES_S: f64 = 5.0;
/// Width of the HUD's contents, points.
const WIDTH: f32 = 250.0;

/// What the HUD's controls edit.
#[derive(Clone, Debug, PartialEq)]
pub struct HudEdit {
    pub controller: &'static str,
    pub tmin_ms: f64,
    pub tmax_ms: f64,
    pub bounds: Bounds,
    pub sweep: bool,
    pub paused: bool,
    /// The temporal mode (`docs/temporal.md`).
    pub temporal: bool,
    /// Whether the refreshes between frames show warps; None without `--warp`.
    pub warps: Option<bool>,
}

/// One edit the view applies at the next frame.
#[derive(Clone, Debug, PartialEq)]
pub enum HudChange {
    Controller(&'static str),
    Band { tmin_ms: f64, tmax_ms: f64 },
    Bounds(Bounds),
    Sweep(bool),
    Pause(bool),
    Temporal(bool),
    Warps(bool),
}

impl HudEdit {
    /// What changed from `before` to `self`.
    pub fn changes_since(&self, before: &HudEdit) -> Vec<HudChange> {
        let mut changes = Vec::new();
        if self.controller != before.controller {
            changes.push(HudChange::Controller(self.controller));
        }
        if (self.tmin_ms, self.tmax_ms) != (before.tmin_ms, before.tmax_ms) {
            changes.push(HudChange::Band {
                tmin_ms: self.tmin_ms,
                tmax_ms: self.tmax_ms,
            });
        }
        if self.bounds != before.bounds {
            changes.push(HudChange::Bounds(self.bounds));
        }
        if self.sweep != before.sweep {
            changes.push(HudChange::Sweep(self.sweep));
        }
        if self.paused != before.paused {
            changes.push(HudChange::Pause(self.paused));
        }
        if self.temporal != before.temporal {
            changes.push(HudChange::Temporal(self.temporal));
        }
        if let (Some(on), true) = (self.warps, self.warps != before.warps) {
            changes.push(HudChange::Warps(on));
        }
        changes
    }
}

/// What the HUD shows besides the controls.
pub struct HudFacts<'a> {
    pub history: &'a FrameHistory,
    pub band: Band,
    /// The backend and device.
    pub device: &'a str,
    /// Where frame times come from (GPU timestamps, wall clock, a recording).
    pub timing: &'a str,
    /// The size of the last frame, pixels.
    pub frame_size: (u32, u32),
    /// Playback: the frame shown and the recording's length; None when live.
    pub playback: Option<(usize, usize)>,
    /// A message to show (e.g. a refused change).
    pub message: Option<&'a str>,
    /// The last frame's motion on screen, degrees of visual angle per second (live only).
    pub speed_deg_s: Option<f64>,
    /// The frame time the controller chose, ms (`perceptual` only).
    pub target_ms: Option<f64>,
    /// Warped refreshes after each frame and the last one's cost, ms (`--warp` only).
    pub warps: Option<(u32, Option<f64>)>,
}

/// Draws the HUD; returns its area in points.
pub fn show(ctx: &egui::Context, edit: &mut HudEdit, facts: &HudFacts<'_>) -> Option<Rect> {
    let window = egui::Window::new("steadyray")
        .anchor(egui::Align2::LEFT_TOP, [6.0, 6.0])
        .resizable(false)
        .collapsible(true)
        .default_width(WIDTH)
        .frame(egui::Frame::window(&ctx.global_style()).fill(Color32::from_black_alpha(200)));
    let response = window.show(ctx, |ui| {
        ui.set_width(WIDTH);
        ui.add(egui::Label::new(egui::RichText::new(facts.device).small()).truncate());
        graph(ui, facts.history, facts.band);
        figures(ui, facts);
        ui.separator();
        controls(ui, edit, facts.playback.is_some());
        if let Some(message) = facts.message {
            ui.colored_label(Color32::from_rgb(255, 120, 100), message);
        }
        ui.small(
            "F1 HUD · Space sweep · P pause · T temporal · V warps · F12 shot\ndrag: look · \
             WASD/QE: move",
        );
    })?;
    Some(response.response.rect)
}

/// The scrolling frame-time graph over the last [`HISTORY_S`] seconds: render time (yellow),
/// presentation interval (grey), the band shaded green.
fn graph(ui: &mut egui::Ui, history: &FrameHistory, band: Band) {
    let (response, painter) = ui.allocate_painter(vec2(WIDTH, 70.0), Sense::hover());
    let rect = response.rect;
    painter.rect_filled(rect, 2.0, Color32::from_black_alpha(160));
    let Some(last) = history.last() else {
        return;
    };
    let now = last.t_s;
    // Room for twice the band's top, more for slow frames (up to four times); the
    // presentation interval may run off the top.
    let p95 = history.render_spread(HISTORY_S).map_or(0.0, |s| s.p95);
    let top_ms = p95.clamp(band.tmax_ms() * 2.0, band.tmax_ms() * 4.0);
    let y = |ms: f64| rect.bottom() - (ms / top_ms).min(1.0) as f32 * rect.height();
    let x = |t_s: f64| rect.right() - ((now - t_s) / HISTORY_S) as f32 * rect.width();
    let band_rect = Rect::from_x_y_ranges(rect.x_range(), y(band.tmax_ms())..=y(band.tmin_ms()));
    painter.rect_filled(
        band_rect,
        0.0,
        Color32::from_rgba_unmultiplied(60, 200, 90, 70),
    );
    let line = |values: Vec<Pos2>, colour: Color32| {
        if values.len() > 1 {
            painter.add(Shape::line(values, Stroke::new(1.5, colour)));
        }
    };
    line(
        history
            .samples()
            .filter_map(|s| s.present_ms.map(|p| Pos2::new(x(s.t_s), y(p))))
            .collect(),
        Color32::from_gray(150),
    );
    line(
        history
            .samples()
            .map(|s| Pos2::new(x(s.t_s), y(s.render_ms)))
            .collect(),
        Color32::from_rgb(255, 210, 60),
    );
    painter.text(
        rect.left_top() + vec2(3.0, 2.0),
        egui::Align2::LEFT_TOP,
        format!("{top_ms:.0} ms"),
        egui::FontId::monospace(10.0),
        Color32::from_gray(200),
    );
}

/// The numbers under the graph.
fn figures(ui: &mut egui::Ui, facts: &HudFacts<'_>) {
    let h = facts.history;
    let ms = |v: Option<f64>| v.map_or("–".to_string(), |v| format!("{v:.1} ms"));
    let last = h.last();
    let render = h.render_spread(FIGURES_S);
    let present = h.present_spread(FIGURES_S);
    egui::Grid::new("figures").num_columns(2).show(ui, |ui| {
        ui.colored_label(Color32::from_rgb(255, 210, 60), "render (Tp)");
        ui.label(format!(
            "{}  p95 {}",
            ms(last.map(|s| s.render_ms)),
            ms(render.map(|s| s.p95))
        ));
        ui.end_row();
        ui.colored_label(Color32::from_gray(170), "present");
        ui.label(format!(
            "{}  {:.0} fps",
            ms(present.map(|s| s.mean)),
            present.map_or(0.0, |s| 1e3 / s.mean)
        ));
        ui.end_row();
        ui.label("in band");
        ui.label(format!(
            "{}  [{}, {}] ms",
            h.in_band_pct(facts.band, FIGURES_S)
                .map_or("–".into(), |p| format!("{p:.0} %")),
            facts.band.tmin_ms(),
            facts.band.tmax_ms()
        ));
        ui.end_row();
        match facts.playback {
            Some((frame, frames)) => {
                ui.label("playback");
                ui.label(format!("frame {} of {frames}", frame + 1));
            }
            None => {
                let q = last.map_or(Quality::new(0.0, 0, 0.0), |s| s.quality);
                ui.label("S  R  scale");
                ui.label(format!("{:.2}  {}  {:.2}", q.spp, q.depth, q.scale));
                ui.end_row();
                ui.label("rays/s");
                ui.label(
                    h.rays_per_s(FIGURES_S)
                        .map_or("–".into(), |r| format!("{:.1} M", r / 1e6)),
                );
                ui.end_row();
                ui.label("motion");
                ui.label(
                    facts
                        .speed_deg_s
                        .map_or("–".into(), |v| format!("{v:.1} °/s on screen")),
                );
                if let Some(target) = facts.target_ms {
                    ui.end_row();
                    ui.label("target");
                    ui.label(format!("{target:.1} ms ({:.0} fps)", 1e3 / target));
                }
                if let Some((warps, last_ms)) = facts.warps {
                    ui.end_row();
                    ui.label("warps");
                    ui.label(format!("{warps} a frame, {}", ms(last_ms)));
                }
            }
        }
        ui.end_row();
        ui.label("frame");
        ui.label(format!(
            "{}x{}  ({})",
            facts.frame_size.0, facts.frame_size.1, facts.timing
        ));
        ui.end_row();
    });
}

/// The controller, band, bounds, sweep, pause, temporal and warps controls.
fn controls(ui: &mut egui::Ui, edit: &mut HudEdit, playback: bool) {
    if !playback {
        egui::ComboBox::from_label("controller")
            .selected_text(edit.controller)
            .show_ui(ui, |ui| {
                for name in CONTROLLER_NAMES {
                    ui.selectable_value(&mut edit.controller, name, name);
                }
            });
    }
    ui.add(
        egui::Slider::new(&mut edit.tmin_ms, 1.0..=100.0)
            .logarithmic(true)
            .text("Tmin ms"),
    );
    ui.add(
        egui::Slider::new(&mut edit.tmax_ms, 1.0..=200.0)
            .logarithmic(true)
            .text("Tmax ms"),
    );
    if !playback {
        ui.collapsing("bounds", |ui| {
            let b = &mut edit.bounds;
            ui.add(
                egui::Slider::new(&mut b.spp_min, 1.0..=256.0)
                    .logarithmic(true)
                    .text("S min"),
            );
            ui.add(
                egui::Slider::new(&mut b.spp_max, 1.0..=256.0)
                    .logarithmic(true)
                    .text("S max"),
            );
            ui.add(egui::Slider::new(&mut b.depth_min, 0..=MAX_DEPTH).text("R min"));
            ui.add(egui::Slider::new(&mut b.depth_max, 0..=MAX_DEPTH).text("R max"));
            ui.add(egui::Slider::new(&mut b.scale_min, 0.05..=1.0).text("scale min"));
            ui.add(egui::Slider::new(&mut b.scale_max, 0.05..=1.0).text("scale max"));
        });
    }
    ui.horizontal(|ui| {
        if !playback {
            ui.checkbox(&mut edit.sweep, "sweep");
        }
        ui.checkbox(&mut edit.paused, "pause");
        if !playback {
            ui.checkbox(&mut edit.temporal, "temporal");
        }
        if let Some(warps) = &mut edit.warps {
            ui.checkbox(warps, "warps");
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::view::history::Sample;

    fn edit() -> HudEdit {
        HudEdit {
            controller: "predictive",
            tmin_ms: 15.0,
            tmax_ms: 20.0,
            bounds: Bounds::default(),
            sweep: false,
            paused: false,
            temporal: false,
            warps: Some(true),
        }
    }

    #[test]
    fn reports_each_edit_once() {
        let before = edit();
        assert!(before.changes_since(&before).is_empty());
        let mut after = before.clone();
        after.controller = "step";
        after.tmax_ms = 25.0;
        after.bounds.depth_max = 4;
        after.sweep = true;
        after.paused = true;
        after.temporal = true;
        after.warps = Some(false);
        let bounds = Bounds {
            depth_max: 4,
            ..Bounds::default()
        };
        assert_eq!(
            after.changes_since(&before),
            [
                HudChange::Controller("step"),
                HudChange::Band {
                    tmin_ms: 15.0,
                    tmax_ms: 25.0
                },
                HudChange::Bounds(bounds),
                HudChange::Sweep(true),
                HudChange::Pause(true),
                HudChange::Temporal(true),
                HudChange::Warps(false),
            ]
        );
        // A window without `--warp` has no warps to turn on.
        let plain = HudEdit {
            warps: None,
            ..before.clone()
        };
        assert!(plain.changes_since(&before).is_empty());
    }

    /// The HUD lays out without a window: egui runs headless.
    #[test]
    fn draws_headless_in_the_top_left_corner() {
        let ctx = egui::Context::default();
        let mut history = FrameHistory::default();
        for i in 0..50 {
            history.push(Sample {
                t_s: i as f64 * 0.02,
                render_ms: 10.0 + (i % 7) as f64,
                present_ms: Some(16.7),
                quality: Quality::new(2.0, 8, 1.0),
                rays: 100_000,
            });
        }
        let facts = HudFacts {
            history: &history,
            band: Band::PAPER,
            device: "test device",
            timing: "GPU timestamps",
            frame_size: (160, 90),
            playback: None,
            message: Some("refused"),
            speed_deg_s: Some(12.5),
            target_ms: Some(1000.0 / 30.0),
            warps: Some((1, Some(6.2))),
        };
        let input = egui::RawInput {
            screen_rect: Some(Rect::from_min_size(Pos2::ZERO, vec2(640.0, 480.0))),
            ..Default::default()
        };
        let mut edit = edit();
        let mut rect = None;
        // egui sizes windows over a few passes.
        for _ in 0..3 {
            let mut output = ctx.run_pass(input.clone(), |ctx| rect = show(ctx, &mut edit, &facts));
            assert!(!output.shapes.is_empty());
            output.textures_delta.clear();
        }
        let rect = rect.expect("the HUD is shown");
        assert!(rect.min.x < 20.0 && rect.min.y < 20.0, "{rect:?}");
        assert!(rect.width() >= WIDTH && rect.width() < 320.0, "{rect:?}");
        assert_eq!(edit, self::edit(), "drawing alone changes nothing");
    }
}
