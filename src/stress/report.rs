//! The stress run's results: one row per case and variant, totals, the text table printed at
//! the end, and `stress.json` / `stress.md`.

use super::cases::{Case, Variant, DRIFT_TOLERANCE};
use crate::bench::sheet::{Cell, Column, Sheet};
use crate::renderer::RenderConfig;
use crate::vk::DeviceInfo;
use serde::Serialize;
use std::fmt::Write as _;

/// One case under one variant.
#[derive(Clone, Debug, Serialize)]
pub struct CaseResult {
    pub case: String,
    pub what: &'static str,
    pub effects: &'static str,
    pub reuse: bool,
    pub size: [u32; 2],
    pub rotation_limit: u32,
    pub frames: u64,
    pub resizes: u32,
    /// Images audited (one reduction each), over all audits of the case.
    pub audits: u32,
    /// Channel values the audits looked at.
    pub values_checked: u64,
    pub nan: u64,
    pub inf: u64,
    pub negative: u64,
    /// Largest |rgb| in any history, and largest estimate count (history alpha).
    pub max_history_value: f32,
    pub max_history_count: f32,
    /// Output RMSE (0..1) of the converged view against a fresh convergence.
    pub drift_rmse: Option<f32>,
    /// Long run: resident host memory growth per frame after its first tenth (bytes).
    pub memory_growth_per_frame: Option<f64>,
    pub validation_messages: usize,
    pub seconds: f64,
    pub failures: Vec<String>,
}

impl CaseResult {
    pub fn new(case: &Case, variant: Variant, config: &RenderConfig) -> Self {
        Self {
            case: case.name.clone(),
            what: case.what,
            effects: variant.effects,
            reuse: variant.reuse,
            size: [config.width, config.height],
            rotation_limit: config.temporal.rotation_limit,
            frames: 0,
            resizes: 0,
            audits: 0,
            values_checked: 0,
            nan: 0,
            inf: 0,
            negative: 0,
            max_history_value: 0.0,
            max_history_count: 0.0,
            drift_rmse: None,
            memory_growth_per_frame: None,
            validation_messages: 0,
            seconds: 0.0,
            failures: Vec::new(),
        }
    }

    /// Record a failure (each distinct message once).
    pub fn fail(&mut self, message: String) {
        if !self.failures.contains(&message) {
            self.failures.push(message);
        }
    }

    pub fn passed(&self) -> bool {
        self.failures.is_empty()
    }

    fn variant(&self) -> String {
        format!(
            "{}/{}",
            self.effects,
            if self.reuse { "reuse" } else { "no-reuse" }
        )
    }
}

/// The table of `stress.md`, one row per case and variant.
fn sheet() -> Sheet<'static, CaseResult> {
    type Of = fn(&CaseResult) -> Cell;
    let columns: [(&str, Of); 14] = [
        ("case", |r| Cell::text(&r.case)),
        ("variant", |r| Cell::text(r.variant())),
        ("size", |r| {
            Cell::text(format!("{}x{}", r.size[0], r.size[1]))
        }),
        ("frames", |r| Cell::int(r.frames)),
        ("values", |r| Cell::int(r.values_checked)),
        ("NaN", |r| Cell::int(r.nan)),
        ("Inf", |r| Cell::int(r.inf)),
        ("neg", |r| Cell::int(r.negative)),
        ("max history", |r| Cell::Sci(r.max_history_value.into())),
        ("max count", |r| Cell::text(r.max_history_count.to_string())),
        ("drift RMSE", |r| Cell::num(r.drift_rmse.map(f64::from), 4)),
        ("validation", |r| Cell::int(r.validation_messages)),
        ("s", |r| Cell::Num(r.seconds, 1)),
        ("result", |r| {
            Cell::text(if r.passed() {
                "ok".to_string()
            } else {
                format!("FAIL: {}", r.failures.join("; "))
            })
        }),
    ];
    Sheet::new(columns.map(|(h, of)| Column::md(h, of)).into())
}

/// Sums over every row.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Totals {
    pub cases: usize,
    pub frames: u64,
    pub values_checked: u64,
    pub failures: usize,
}

#[derive(Clone, Debug, Serialize)]
pub struct StressReport {
    pub command: String,
    pub device: String,
    pub driver: String,
    pub quick: bool,
    pub drift_tolerance: f32,
    pub totals: Totals,
    pub results: Vec<CaseResult>,
}

impl StressReport {
    pub fn new(command: String, info: &DeviceInfo, quick: bool, results: Vec<CaseResult>) -> Self {
        let totals = Totals {
            cases: results.len(),
            frames: results.iter().map(|r| r.frames).sum(),
            values_checked: results.iter().map(|r| r.values_checked).sum(),
            failures: results.iter().filter(|r| !r.passed()).count(),
        };
        Self {
            command,
            device: info.name.clone(),
            driver: info.driver.clone(),
            quick,
            drift_tolerance: DRIFT_TOLERANCE,
            totals,
            results,
        }
    }

    /// The table printed at the end and kept as `stress.md`.
    pub fn markdown(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "# ssgi stress\n");
        let _ = writeln!(s, "Command: `{}`  ", self.command);
        let _ = writeln!(s, "Device: {} ({})\n", self.device, self.driver);
        let t = &self.totals;
        let _ = writeln!(
            s,
            "{} cases, {} frames, {} values checked, {} failed.\n",
            t.cases, t.frames, t.values_checked, t.failures
        );
        s += &sheet().markdown(&self.results);
        let _ = writeln!(
            s,
            "\nValues: every channel of every float target and history, counted on the GPU \
             after the moving frames and after the static hold (and every audit period of the \
             long run). Drift: output RMSE of the held view against the same view converged \
             from scratch (bound {}).",
            self.drift_tolerance
        );
        s
    }

    /// One line per row for the terminal as the run goes.
    pub fn line(r: &CaseResult) -> String {
        let status = if r.passed() {
            "ok".to_string()
        } else {
            format!("FAIL ({})", r.failures.join("; "))
        };
        format!(
            "{:<28} {:<14} {:>5}x{:<4} {:>7} frames {:>6.1} s  {status}",
            r.case,
            r.variant(),
            r.size[0],
            r.size[1],
            r.frames,
            r.seconds
        )
    }
}
