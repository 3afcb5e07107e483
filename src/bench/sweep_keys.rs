//! The parameters `ssgi sweep --vary KEY=V1,V2,...` can vary, and the cartesian product of the
//! values given. Values use the command line's syntax and parsers (`--pcf`, `--vpls`,
//! `--reuse`, ...), so a sweep accepts exactly what a single run accepts.

use crate::config::parse::{
    parse_bias, parse_ema_alpha, parse_epsilon, parse_fraction, parse_gate, parse_on_off,
    parse_pattern_count, parse_vpls, AccumulateMode,
};
use crate::config::{Accumulate, AoConfig, AoEstimator, HistoryResample, Refresh};
use crate::effects::ssdo::config::{parse_bilateral, parse_ssdo_scale};
use crate::effects::ssdo::config::{SsdoConfig, SsdoForm};
use crate::error::{Error, Result};
use crate::renderer::frame::Pcf;
use crate::renderer::RenderConfig;
use clap::ValueEnum;
use std::fmt;

/// Most combinations one sweep may expand to: far beyond any useful run, small enough that a
/// typo such as ten keys of ten values fails with a message instead of exhausting memory.
pub const MAX_COMBINATIONS: usize = 4096;

/// A render parameter a sweep can vary.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Key {
    AoSamples,
    AoEstimator,
    AoRadius,
    AoPatterns,
    AoPositionMips,
    Reuse,
    Accumulate,
    Refresh,
    RefreshBudget,
    RotationLimit,
    Epsilon,
    Resample,
    Reaccumulate,
    Vpls,
    Interleave,
    Visibility,
    HalfRes,
    Pcf,
    RsmSize,
    SsdoForm,
    SsdoSamples,
    SsdoRadius,
    SsdoFilter,
    SsdoScale,
}

impl Key {
    /// Every key, in the order `help_table` lists them.
    pub const ALL: [Key; 24] = [
        Key::AoSamples,
        Key::AoEstimator,
        Key::AoRadius,
        Key::AoPatterns,
        Key::AoPositionMips,
        Key::Reuse,
        Key::Accumulate,
        Key::Refresh,
        Key::RefreshBudget,
        Key::RotationLimit,
        Key::Epsilon,
        Key::Resample,
        Key::Reaccumulate,
        Key::Vpls,
        Key::Interleave,
        Key::Visibility,
        Key::HalfRes,
        Key::Pcf,
        Key::RsmSize,
        Key::SsdoForm,
        Key::SsdoSamples,
        Key::SsdoRadius,
        Key::SsdoFilter,
        Key::SsdoScale,
    ];

    /// The name given to `--vary`: the field's path in `RenderConfig`.
    pub fn name(self) -> &'static str {
        match self {
            Key::AoSamples => "ao.samples",
            Key::AoEstimator => "ao.estimator",
            Key::AoRadius => "ao.radius",
            Key::AoPatterns => "ao.patterns",
            Key::AoPositionMips => "ao.position_mips",
            Key::Reuse => "temporal.reuse",
            Key::Accumulate => "temporal.accumulate",
            Key::Refresh => "temporal.refresh",
            Key::RefreshBudget => "temporal.refresh_budget",
            Key::RotationLimit => "temporal.rotation_limit",
            Key::Epsilon => "temporal.epsilon",
            Key::Resample => "temporal.resample",
            Key::Reaccumulate => "temporal.reaccumulate",
            Key::Vpls => "indirect.vpls",
            Key::Interleave => "indirect.interleave",
            Key::Visibility => "indirect.visibility",
            Key::HalfRes => "indirect.half_res",
            Key::Pcf => "pcf",
            Key::RsmSize => "rsm_size",
            Key::SsdoForm => "ssdo.form",
            Key::SsdoSamples => "ssdo.samples",
            Key::SsdoRadius => "ssdo.radius",
            Key::SsdoFilter => "ssdo.filter",
            Key::SsdoScale => "ssdo.scale",
        }
    }

    pub fn description(self) -> &'static str {
        match self {
            Key::AoSamples => "SSAO samples per pattern (--ao-samples)",
            Key::AoEstimator => "SSAO estimator (--ao)",
            Key::AoRadius => "SSAO sampling radius, fraction of the scene's bounding radius",
            Key::AoPatterns => "SSAO patterns evaluated at once per frame",
            Key::AoPositionMips => {
                "far SSAO taps read position levels up to this; 0 = off (--ao-position-mips)"
            }
            Key::Reuse => "reverse-reprojection reuse; off = no-reuse baseline (--reuse)",
            Key::Accumulate => {
                "history merge, default parameter if none; mean alone caps at the rotation limit"
            }
            Key::Refresh => {
                "tiled refresh, one tile recomputed per frame; hard = the thesis's seams"
            }
            Key::RefreshBudget => {
                "refresh work per frame, share of a full frame's (--refresh-budget)"
            }
            Key::RotationLimit => "patterns per pixel before it counts as converged",
            Key::Epsilon => "disocclusion threshold: pixel footprints, or abs: world units",
            Key::Resample => "history read between texels under motion (--history-resample)",
            Key::Reaccumulate => "histories re-accumulate when the camera stops (--reaccumulate)",
            Key::Vpls => "VPLs gathered per pixel and frame; all = every RSM texel (--vpls)",
            Key::Interleave => "interleaved gather: NxN blocks share the VPLs (--interleave)",
            Key::Visibility => "screen-space visibility test per VPL (--vpl-visibility)",
            Key::HalfRes => "indirect gather at half resolution (--half-res)",
            Key::Pcf => "shadow filtering kernel (--pcf)",
            Key::RsmSize => "side of the (reflective) shadow map in texels (--rsm-size)",
            Key::SsdoForm => "SSDO in one pass, Ritschel's two, or SSAO on its pipeline (--ssdo)",
            Key::SsdoSamples => "SSDO hemisphere samples per pixel (--ssdo-samples)",
            Key::SsdoRadius => "SSDO hemisphere radius, fraction of the scene's bounding radius",
            Key::SsdoFilter => "SSDO's separable bilateral filter side (--bilateral)",
            Key::SsdoScale => "SSDO's resolution, upsampled when half (--ssdo-scale)",
        }
    }

    /// The values accepted, as shown in errors and `help_table`.
    pub fn syntax(self) -> &'static str {
        match self {
            Key::AoSamples => "integer 1..=4096",
            Key::AoEstimator => "thesis|crytek|szentandrasi",
            Key::AoRadius => "number in (0, 10]",
            Key::AoPatterns => "integer 1..=1024",
            Key::AoPositionMips => "integer 0..=3",
            Key::Reuse | Key::Reaccumulate | Key::Visibility | Key::HalfRes => "on|off",
            Key::Refresh => "feathered|on|hard|off",
            Key::RefreshBudget => "PERCENT% or fraction in (0, 100]",
            Key::Accumulate => "gated[:SIGMAS]|confidence[:BIAS]|ema[:ALPHA]|mean[:CAP]",
            Key::RotationLimit => "integer 1..=2048",
            Key::Epsilon => "NUMBER|abs:NUMBER",
            Key::Resample => "bilinear|point",
            Key::Vpls => "integer 1..=16384|all",
            Key::Interleave => "integer 1..=8",
            Key::Pcf => "hard|9|SQUARE (25, 49, ...)|disc:N",
            Key::RsmSize => "integer 1..=16384",
            Key::SsdoForm => "one-step|two-step|ssao",
            Key::SsdoSamples => "integer 1..=4096",
            Key::SsdoRadius => "number in (0, 10]",
            Key::SsdoFilter => "odd integer 1..=31|off",
            Key::SsdoScale => "1|0.5",
        }
    }

    /// The key called `name`; an unknown name gets every valid key in the error.
    pub fn parse(name: &str) -> Result<Key> {
        let name = name.trim();
        Key::ALL
            .into_iter()
            .find(|k| k.name() == name)
            .ok_or_else(|| {
                let known: Vec<&str> = Key::ALL.iter().map(|k| k.name()).collect();
                Error::Config(format!(
                    "unknown --vary key {name:?}; valid keys: {}",
                    known.join(", ")
                ))
            })
    }
}

impl fmt::Display for Key {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// One `--vary KEY=V1,V2,...`: the values stay strings (trimmed) so reports can label each
/// combination exactly as the user wrote it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Vary {
    pub key: Key,
    pub values: Vec<String>,
}

/// Parse `KEY=V1,V2,...`. Every value is checked here, so a typo fails before any rendering;
/// two values that set the same thing (`on,yes`, `hard,1`) are rejected as duplicates.
pub fn parse_vary(s: &str) -> Result<Vary> {
    let (name, list) = s.split_once('=').ok_or_else(|| {
        Error::Config(format!(
            "--vary takes KEY=V1,V2,..., not {:?} (no '=')",
            s.trim()
        ))
    })?;
    let key = Key::parse(name)?;
    let values: Vec<String> = list.split(',').map(|v| v.trim().to_string()).collect();
    if values.iter().any(String::is_empty) {
        return Err(Error::Config(format!(
            "--vary {key}: empty value in {:?} (expected {})",
            list.trim(),
            key.syntax()
        )));
    }
    let mut settings: Vec<(&str, Setting)> = Vec::with_capacity(values.len());
    for v in &values {
        let setting = Setting::parse(key, v)?;
        if let Some((first, _)) = settings.iter().find(|(_, s)| *s == setting) {
            return Err(Error::Config(format!(
                "--vary {key}: {first:?} and {v:?} set the same value; give each once"
            )));
        }
        settings.push((v, setting));
    }
    Ok(Vary { key, values })
}

/// Set `key`'s field of `config` to `value`. Only the value's syntax and the command line's
/// range checks happen here; `RenderConfig::validate` is the caller's job, since a value may be
/// valid or not depending on the other fields (`indirect.vpls=all` needs a small `rsm_size`).
pub fn apply(config: &mut RenderConfig, key: Key, value: &str) -> Result<()> {
    // Setting::parse gives Count and Flag only for the keys matched below.
    match Setting::parse(key, value.trim())? {
        Setting::Count(n) => match key {
            Key::AoSamples => config.ao.samples = n,
            Key::AoPatterns => config.ao.patterns = n,
            Key::AoPositionMips => config.ao.position_mips = n,
            Key::RotationLimit => config.temporal.rotation_limit = n,
            Key::Vpls => config.indirect.vpls = n,
            Key::Interleave => config.indirect.interleave = n,
            Key::SsdoSamples => config.ssdo.samples = n,
            _ => config.rsm_size = n,
        },
        Setting::Flag(on) => match key {
            Key::Reuse => config.temporal.reuse = on,
            Key::Reaccumulate => config.temporal.reaccumulate = on,
            Key::Visibility => config.indirect.visibility = on,
            _ => config.indirect.half_res = on,
        },
        Setting::Radius(r) if key == Key::SsdoRadius => config.ssdo.radius = r,
        Setting::Radius(r) => config.ao.radius = r,
        Setting::Form(f) => config.ssdo.form = f,
        Setting::Filter(side) => config.ssdo.filter = side,
        Setting::Divisor(d) => config.ssdo.scale = d,
        Setting::Estimator(e) => config.ao.estimator = e,
        Setting::Refresh(r) => config.temporal.refresh = r,
        Setting::Resample(r) => config.temporal.resample = r,
        Setting::Budget(b) => config.temporal.refresh_budget = b,
        Setting::Accumulate(a) => config.temporal.accumulate = a,
        Setting::MeanOfLimit => {
            config.temporal.accumulate = Accumulate::Mean {
                cap: config.temporal.rotation_limit,
            }
        }
        Setting::Epsilon(e) => config.temporal.epsilon = e,
        Setting::Pcf(p) => config.pcf = p,
    }
    Ok(())
}

/// A combination's (key, value) pairs, in `--vary` order, values as the user wrote them.
pub type Label = Vec<(Key, String)>;

/// Every combination of the values of `varies` applied to `base`, first `--vary` outermost
/// (it changes slowest), each labelled with its (key, value) pairs in `--vary` order and
/// validated. `temporal.accumulate` is applied last so that a bare `mean` caps at the
/// combination's own rotation limit, like `--accumulate mean` without `--mean-cap`.
pub fn combinations(base: &RenderConfig, varies: &[Vary]) -> Result<Vec<(Label, RenderConfig)>> {
    for (i, v) in varies.iter().enumerate() {
        if varies[..i].iter().any(|w| w.key == v.key) {
            return Err(Error::Config(format!(
                "--vary {} is given twice; list all its values in one --vary",
                v.key
            )));
        }
        if v.values.is_empty() {
            return Err(Error::Config(format!("--vary {} has no values", v.key)));
        }
    }
    let count = varies
        .iter()
        .try_fold(1usize, |n, v| n.checked_mul(v.values.len()))
        .filter(|&n| n <= MAX_COMBINATIONS)
        .ok_or_else(|| {
            Error::Config(format!(
                "--vary expands to more than {MAX_COMBINATIONS} combinations; vary fewer keys \
                 or values"
            ))
        })?;
    // Application order: `--vary` order, with temporal.accumulate moved last.
    let mut order: Vec<usize> = (0..varies.len()).collect();
    order.sort_by_key(|&i| varies[i].key == Key::Accumulate);
    let mut out = Vec::with_capacity(count);
    for index in 0..count {
        // Mixed-radix digits of `index`, last --vary fastest.
        let mut picks = vec![0; varies.len()];
        let mut rest = index;
        for (pick, v) in picks.iter_mut().zip(varies).rev() {
            *pick = rest % v.values.len();
            rest /= v.values.len();
        }
        let label: Label = varies
            .iter()
            .zip(&picks)
            .map(|(v, &p)| (v.key, v.values[p].clone()))
            .collect();
        let mut config = *base;
        for &i in &order {
            apply(&mut config, label[i].0, &label[i].1)?;
        }
        if let Err(e) = config.validate() {
            let message = match e {
                Error::Config(m) => m,
                other => other.to_string(),
            };
            return Err(Error::Config(format!(
                "--vary combination {}: {message}",
                describe(&label)
            )));
        }
        out.push((label, config));
    }
    Ok(out)
}

/// `key=value, key=value`: how a combination is named in errors and reports.
pub fn describe(label: &[(Key, String)]) -> String {
    label
        .iter()
        .map(|(k, v)| format!("{k}={v}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The keys, their values and what they change, one per line, for `ssgi sweep --help` and
/// error messages.
pub fn help_table() -> String {
    let rows: Vec<[&str; 3]> = Key::ALL
        .iter()
        .map(|k| [k.name(), k.syntax(), k.description()])
        .collect();
    let width = |c: usize| {
        rows.iter()
            .map(|r| r[c].len())
            .chain([["KEY", "VALUES"][c].len()])
            .max()
            .unwrap_or(0)
    };
    let (w0, w1) = (width(0), width(1));
    let mut out = format!("{:w0$}  {:w1$}  MEANING\n", "KEY", "VALUES");
    for [name, syntax, description] in rows {
        out.push_str(&format!("{name:w0$}  {syntax:w1$}  {description}\n"));
    }
    out
}

/// A parsed value: what `apply` writes, and what makes two values duplicates. A bare `mean`
/// stays distinct from `mean:N` because its cap follows the rotation limit.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Setting {
    Count(u32),
    Flag(bool),
    Radius(f32),
    Estimator(AoEstimator),
    Refresh(Refresh),
    Resample(HistoryResample),
    Budget(f32),
    Accumulate(Accumulate),
    MeanOfLimit,
    Epsilon(crate::config::Epsilon),
    Pcf(Pcf),
    Form(SsdoForm),
    Filter(u32),
    /// A resolution divisor.
    Divisor(u32),
}

impl Setting {
    fn parse(key: Key, value: &str) -> Result<Setting> {
        Setting::parse_inner(key, value).map_err(|why| {
            Error::Config(format!(
                "--vary {key}: invalid value {value:?} ({why}); expected {}",
                key.syntax()
            ))
        })
    }

    fn parse_inner(key: Key, v: &str) -> std::result::Result<Setting, String> {
        let count = |max: u32| match v.parse::<u32>() {
            Ok(n) if (1..=max).contains(&n) => Ok(Setting::Count(n)),
            _ => Err(format!("not an integer in 1..={max}")),
        };
        match key {
            Key::AoSamples => count(4096),
            Key::AoPatterns => count(1024),
            Key::AoPositionMips => match v.parse::<u32>() {
                Ok(n) if n <= AoConfig::MAX_POSITION_MIPS => Ok(Setting::Count(n)),
                _ => Err(format!(
                    "not an integer in 0..={}",
                    AoConfig::MAX_POSITION_MIPS
                )),
            },
            Key::RsmSize => count(crate::renderer::MAX_SIZE),
            Key::RotationLimit => parse_pattern_count(v).map(Setting::Count),
            Key::Vpls => parse_vpls(v).map(Setting::Count),
            Key::Interleave => count(crate::config::IndirectConfig::MAX_INTERLEAVE),
            Key::Refresh => Refresh::from_str(v, false).map(Setting::Refresh),
            Key::Resample => HistoryResample::from_str(v, false).map(Setting::Resample),
            Key::RefreshBudget => parse_fraction(v).map(Setting::Budget),
            Key::Reuse | Key::Reaccumulate | Key::Visibility | Key::HalfRes => {
                parse_on_off(v).map(Setting::Flag)
            }
            Key::SsdoSamples => count(SsdoConfig::MAX_SAMPLES),
            Key::SsdoForm => SsdoForm::from_str(v, false).map(Setting::Form),
            Key::SsdoFilter => parse_bilateral(v).map(Setting::Filter),
            Key::SsdoScale => parse_ssdo_scale(v).map(Setting::Divisor),
            Key::AoRadius | Key::SsdoRadius => match v.parse::<f32>() {
                Ok(r) if r.is_finite() && r > 0.0 && r <= 10.0 => Ok(Setting::Radius(r)),
                _ => Err("not a number in (0, 10]".into()),
            },
            Key::AoEstimator => AoEstimator::from_str(v, false).map(Setting::Estimator),
            Key::Accumulate => parse_accumulate(v),
            Key::Epsilon => parse_epsilon(v).map(Setting::Epsilon),
            Key::Pcf => Pcf::parse(v).map(Setting::Pcf),
        }
    }
}

/// `MODE[:PARAMETER]`: the mode as `--accumulate` takes it, the parameter as `--gate`,
/// `--bias`, `--ema-alpha` or `--mean-cap` takes it; without one, the command line's default.
fn parse_accumulate(v: &str) -> std::result::Result<Setting, String> {
    let (mode, parameter) = match v.split_once(':') {
        Some((m, p)) => (m, Some(p)),
        None => (v, None),
    };
    let mode = AccumulateMode::from_str(mode, false)?;
    Ok(match (mode, parameter) {
        (AccumulateMode::Gated, None) => Setting::Accumulate(Accumulate::GATED),
        (AccumulateMode::Gated, Some(p)) => Setting::Accumulate(Accumulate::Gated {
            sigmas: parse_gate(p)?,
        }),
        (AccumulateMode::Confidence, None) => Setting::Accumulate(Accumulate::CONFIDENCE),
        (AccumulateMode::Confidence, Some(p)) => Setting::Accumulate(Accumulate::Confidence {
            bias: parse_bias(p)?,
        }),
        (AccumulateMode::Ema, p) => Setting::Accumulate(Accumulate::Ema {
            alpha: p.map_or(Ok(Accumulate::EMA_ALPHA), parse_ema_alpha)?,
        }),
        (AccumulateMode::Mean, None) => Setting::MeanOfLimit,
        (AccumulateMode::Mean, Some(p)) => Setting::Accumulate(Accumulate::Mean {
            cap: parse_pattern_count(p)?,
        }),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Epsilon;
    use crate::renderer::frame::PcfKernel;

    fn err(r: Result<impl fmt::Debug>) -> String {
        r.expect_err("expected an error").to_string()
    }

    /// Sets the field a key should set, written out by hand.
    type SetByHand = fn(&mut RenderConfig);

    #[test]
    fn each_key_changes_exactly_its_field() {
        let base = RenderConfig::default();
        let cases: Vec<(Key, &str, SetByHand)> = vec![
            (Key::AoSamples, "16", |c| c.ao.samples = 16),
            (Key::AoEstimator, "crytek", |c| {
                c.ao.estimator = AoEstimator::Crytek
            }),
            (Key::AoRadius, "0.5", |c| c.ao.radius = 0.5),
            (Key::AoPatterns, "8", |c| c.ao.patterns = 8),
            (Key::AoPositionMips, "2", |c| c.ao.position_mips = 2),
            (Key::SsdoForm, "two-step", |c| {
                c.ssdo.form = SsdoForm::TwoStep
            }),
            (Key::SsdoSamples, "50", |c| c.ssdo.samples = 50),
            (Key::SsdoRadius, "0.1", |c| c.ssdo.radius = 0.1),
            (Key::SsdoFilter, "off", |c| c.ssdo.filter = 0),
            (Key::SsdoScale, "0.5", |c| c.ssdo.scale = 2),
            (Key::Reuse, "off", |c| c.temporal.reuse = false),
            (Key::Reaccumulate, "off", |c| {
                c.temporal.reaccumulate = false
            }),
            (Key::Accumulate, "ema:0.25", |c| {
                c.temporal.accumulate = Accumulate::Ema { alpha: 0.25 }
            }),
            (Key::Refresh, "hard", |c| c.temporal.refresh = Refresh::Hard),
            (Key::Resample, "point", |c| {
                c.temporal.resample = HistoryResample::Point
            }),
            (Key::RefreshBudget, "225%", |c| {
                c.temporal.refresh_budget = 2.25
            }),
            (Key::RotationLimit, "64", |c| c.temporal.rotation_limit = 64),
            (Key::Epsilon, "abs:0.1", |c| {
                c.temporal.epsilon = Epsilon::Absolute { epsilon: 0.1 }
            }),
            (Key::Vpls, "all", |c| c.indirect.vpls = 0),
            (Key::Interleave, "2", |c| c.indirect.interleave = 2),
            (Key::Visibility, "on", |c| c.indirect.visibility = true),
            (Key::HalfRes, "off", |c| c.indirect.half_res = false),
            (Key::Pcf, "9", |c| c.pcf = Pcf::NINE),
            (Key::RsmSize, "1024", |c| c.rsm_size = 1024),
        ];
        assert_eq!(cases.len(), Key::ALL.len(), "a key without a test");
        for (key, value, set) in cases {
            let mut expected = base;
            set(&mut expected);
            assert_ne!(expected, base, "{key}={value} must differ from the default");
            let mut got = base;
            apply(&mut got, key, value).unwrap();
            assert_eq!(got, expected, "{key}={value}");
            assert_eq!(Key::parse(key.name()).unwrap(), key);
        }
    }

    #[test]
    fn accumulate_takes_the_command_line_modes_and_parameters() {
        let set = |v: &str| {
            let mut c = RenderConfig::default();
            c.temporal.rotation_limit = 20;
            apply(&mut c, Key::Accumulate, v).map(|_| c.temporal.accumulate)
        };
        assert_eq!(set("gated").unwrap(), Accumulate::GATED);
        assert_eq!(set("gated:3").unwrap(), Accumulate::Gated { sigmas: 3.0 });
        assert_eq!(set("confidence").unwrap(), Accumulate::CONFIDENCE);
        assert_eq!(
            set("confidence:0.5").unwrap(),
            Accumulate::Confidence { bias: 0.5 }
        );
        assert_eq!(
            set("ema").unwrap(),
            Accumulate::Ema {
                alpha: Accumulate::EMA_ALPHA
            }
        );
        assert_eq!(set("mean").unwrap(), Accumulate::Mean { cap: 20 });
        assert_eq!(set("mean:64").unwrap(), Accumulate::Mean { cap: 64 });
        for bad in [
            "ema:0",
            "ema:2",
            "mean:0",
            "mean:5000",
            "confidence:-1",
            "gated:0",
            "median",
        ] {
            let e = err(set(bad));
            assert!(e.contains("temporal.accumulate") && e.contains(bad), "{e}");
            assert!(
                e.contains("gated[:SIGMAS]|confidence[:BIAS]|ema[:ALPHA]|mean[:CAP]"),
                "{e}"
            );
        }
        let mut c = RenderConfig::default();
        apply(&mut c, Key::Pcf, "disc:16").unwrap();
        assert_eq!(c.pcf.kernel, PcfKernel::Disc { samples: 16 });
    }

    #[test]
    fn unknown_key_lists_every_key() {
        let e = err(parse_vary("ao.sample=1,2"));
        assert!(e.contains("\"ao.sample\""), "{e}");
        for k in Key::ALL {
            assert!(e.contains(k.name()), "{e} lacks {k}");
        }
        let table = help_table();
        for k in Key::ALL {
            assert!(
                table.contains(k.name()) && table.contains(k.syntax()),
                "{table}"
            );
        }
        assert_eq!(table.lines().count(), Key::ALL.len() + 1);
    }

    #[test]
    fn bad_values_are_rejected_with_the_syntax() {
        for (s, key, value) in [
            ("ao.samples=8,0", "ao.samples", "0"),
            ("ao.samples=x", "ao.samples", "x"),
            ("ao.estimator=thesis,hbao", "ao.estimator", "hbao"),
            ("ao.radius=0.1,nan", "ao.radius", "nan"),
            ("temporal.reuse=on,maybe", "temporal.reuse", "maybe"),
            ("indirect.vpls=all,20000", "indirect.vpls", "20000"),
            ("pcf=49,50", "pcf", "50"),
            ("rsm_size=99999", "rsm_size", "99999"),
            (
                "temporal.rotation_limit=4096",
                "temporal.rotation_limit",
                "4096",
            ),
        ] {
            let e = err(parse_vary(s));
            let syntax = Key::parse(key).unwrap().syntax();
            assert!(
                e.contains(key) && e.contains(&format!("{value:?}")) && e.contains(syntax),
                "{s}: {e}"
            );
        }
        assert!(err(parse_vary("ao.samples")).contains("no '='"));
        assert!(err(parse_vary("ao.samples=8,,16")).contains("empty value"));
        assert!(err(parse_vary("ao.samples=")).contains("empty value"));
        assert!(err(parse_vary("ao.samples=8, 8")).contains("same value"));
        assert!(err(parse_vary("temporal.reuse=on,yes")).contains("same value"));
        // A bare mean follows the rotation limit, so it is not mean:36.
        assert!(parse_vary("temporal.accumulate=mean,mean:36").is_ok());
        let v = parse_vary(" ao.samples = 8 , 16 ").unwrap();
        assert_eq!(v.key, Key::AoSamples);
        assert_eq!(v.values, ["8", "16"]);
        let mut c = RenderConfig::default();
        assert!(apply(&mut c, Key::AoSamples, "-1").is_err());
        assert_eq!(
            c,
            RenderConfig::default(),
            "a rejected value changes nothing"
        );
    }

    #[test]
    fn combinations_are_the_product_first_vary_outermost() {
        let base = RenderConfig::default();
        let varies = [
            parse_vary("ao.samples=8,16").unwrap(),
            parse_vary("temporal.reuse=on,off").unwrap(),
        ];
        let combos = combinations(&base, &varies).unwrap();
        let labels: Vec<String> = combos.iter().map(|(l, _)| describe(l)).collect();
        assert_eq!(
            labels,
            [
                "ao.samples=8, temporal.reuse=on",
                "ao.samples=8, temporal.reuse=off",
                "ao.samples=16, temporal.reuse=on",
                "ao.samples=16, temporal.reuse=off",
            ]
        );
        let fields: Vec<(u32, bool)> = combos
            .iter()
            .map(|(_, c)| (c.ao.samples, c.temporal.reuse))
            .collect();
        assert_eq!(fields, [(8, true), (8, false), (16, true), (16, false)]);
        let one = combinations(&base, &[]).unwrap();
        assert_eq!(one.len(), 1);
        assert!(one[0].0.is_empty() && one[0].1 == base);
    }

    #[test]
    fn bare_mean_caps_at_each_combinations_rotation_limit() {
        let varies = [
            parse_vary("temporal.accumulate=mean").unwrap(),
            parse_vary("temporal.rotation_limit=16,64").unwrap(),
        ];
        let combos = combinations(&RenderConfig::default(), &varies).unwrap();
        let caps: Vec<Accumulate> = combos.iter().map(|(_, c)| c.temporal.accumulate).collect();
        assert_eq!(
            caps,
            [Accumulate::Mean { cap: 16 }, Accumulate::Mean { cap: 64 }]
        );
    }

    #[test]
    fn duplicate_keys_invalid_and_huge_combinations_are_rejected() {
        let base = RenderConfig::default();
        let twice = [
            parse_vary("ao.samples=8").unwrap(),
            parse_vary("ao.samples=16").unwrap(),
        ];
        assert!(err(combinations(&base, &twice)).contains("ao.samples is given twice"));
        // Every RSM texel per pixel needs a small shadow map.
        let varies = [
            parse_vary("indirect.vpls=64,all").unwrap(),
            parse_vary("rsm_size=128,512").unwrap(),
        ];
        let e = err(combinations(&base, &varies));
        assert!(
            e.contains("indirect.vpls=all, rsm_size=512") && e.contains("--rsm-size 128"),
            "{e}"
        );
        let many: Vec<Vary> = ["ao.samples", "ao.patterns", "rsm_size"]
            .iter()
            .map(|k| {
                let values = (1..=20).map(|n| n.to_string()).collect::<Vec<_>>();
                parse_vary(&format!("{k}={}", values.join(","))).unwrap()
            })
            .collect();
        assert!(err(combinations(&base, &many)).contains("more than 4096"));
    }
}
