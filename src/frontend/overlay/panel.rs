//! The overlay's contents, laid out by egui: the device, the frame rate, per-group and
//! per-pass GPU time (median and p95 over the last second, with bars), the counters and the
//! lane efficiency of the passes that count their invocations.

use super::history::{Row, Window};
use egui::{Color32, RichText};

/// Bar length of the slowest row, in points.
const BAR_POINTS: f32 = 90.0;
const MEDIAN_BAR: Color32 = Color32::from_rgb(90, 170, 250);
const P95_TICK: Color32 = Color32::from_rgb(250, 180, 60);

/// What the panel shows besides the statistics.
pub struct Header<'a> {
    /// Device and driver.
    pub device: &'a str,
    /// Render size, displayed buffer and switches.
    pub view: &'a str,
}

/// Lay out the panel into `ui`.
pub fn show(ui: &mut egui::Ui, header: &Header<'_>, w: &Window) {
    ui.label(RichText::new(header.device).strong());
    ui.label(header.view);
    let fps = match w.frame_ms {
        Some(ms) => format!("{ms:6.2} ms/frame  {:5.1} fps", w.fps),
        None => "waiting for frames".to_string(),
    };
    ui.label(fps);
    if w.skipped > 0 {
        ui.label(format!(
            "{} of {} frames skipped (nothing changed)",
            w.skipped, w.timed
        ));
    }
    let scale = [w.total.as_ref()]
        .into_iter()
        .flatten()
        .chain(w.groups.iter().map(|g| &g.group))
        .chain(w.other.iter())
        .map(|r| r.time.p95)
        .fold(0.0_f64, f64::max);
    egui::Grid::new("overlay timings")
        .num_columns(4)
        .spacing([8.0, 1.0])
        .show(ui, |ui| {
            ui.label(RichText::new("GPU ms").underline());
            ui.label("median");
            ui.label("p95");
            ui.label("");
            ui.end_row();
            if let Some(total) = &w.total {
                row(ui, total, 0, scale);
            }
            for g in &w.groups {
                row(ui, &g.group, 0, scale);
                // A group of one pass of its own name says it once.
                if !(g.passes.len() == 1 && g.passes[0].name == g.group.name) {
                    for p in &g.passes {
                        row(ui, p, 1, scale);
                    }
                }
            }
            for p in &w.other {
                row(ui, p, 0, scale);
            }
        });
    let counters: Vec<_> = w
        .counters
        .iter()
        .filter(|(n, mean)| {
            *mean > 0.0 && !n.ends_with("_invocations") && !n.ends_with("_serial_evaluations")
        })
        .collect();
    if !counters.is_empty() || !w.lane_efficiency.is_empty() {
        ui.separator();
        egui::Grid::new("overlay counters")
            .num_columns(2)
            .spacing([8.0, 1.0])
            .show(ui, |ui| {
                for (name, mean) in counters {
                    ui.label(*name);
                    ui.label(format!("{mean:>10.0}"));
                    ui.end_row();
                }
                for (pass, e) in &w.lane_efficiency {
                    ui.label(format!("{pass} lanes active"));
                    ui.label(format!("{:>9.1}%", 100.0 * e));
                    ui.end_row();
                }
            });
    }
    ui.label(RichText::new("H hides, O compacts, F1 prints the keys").weak());
}

/// The compact summary (the overlay in a small window): the frame rate and the GPU total,
/// and the key to the full panel.
pub fn show_compact(ui: &mut egui::Ui, w: &Window) {
    let fps = match w.frame_ms {
        Some(ms) => format!("{ms:6.2} ms/frame {:5.1} fps", w.fps),
        None => "waiting for frames".to_string(),
    };
    ui.label(fps);
    if let Some(total) = &w.total {
        ui.label(format!(
            "GPU {:.3} ms (p95 {:.3})",
            total.time.median, total.time.p95
        ));
    }
    ui.label(RichText::new("O full panel, H hides").weak());
}

/// One timing row: name (indented by `depth`), median, p95 and a bar (median filled, p95
/// ticked) on a common `scale`.
fn row(ui: &mut egui::Ui, r: &Row, depth: usize, scale: f64) {
    let name = format!("{}{}", "  ".repeat(depth), r.name);
    ui.label(if depth == 0 {
        RichText::new(name).strong()
    } else {
        RichText::new(name)
    });
    ui.label(format!("{:7.3}", r.time.median));
    ui.label(format!("{:7.3}", r.time.p95));
    let (rect, _) = ui.allocate_exact_size(
        egui::vec2(
            BAR_POINTS,
            ui.text_style_height(&egui::TextStyle::Body) * 0.6,
        ),
        egui::Sense::hover(),
    );
    // Guarded: no timing yet (scale 0) or a NaN median draws no bar.
    let frac = |ms: f64| {
        if scale > 0.0 && ms.is_finite() {
            (ms / scale).clamp(0.0, 1.0) as f32
        } else {
            0.0
        }
    };
    let painter = ui.painter();
    let mut bar = rect;
    bar.set_width(rect.width() * frac(r.time.median));
    painter.rect_filled(bar, 0.0, MEDIAN_BAR);
    let x = rect.left() + rect.width() * frac(r.time.p95);
    painter.vline(x, rect.y_range(), egui::Stroke::new(1.5, P95_TICK));
    ui.end_row();
}
