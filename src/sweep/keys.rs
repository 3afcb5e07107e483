//! The parameters `ssgi sweep --vary KEY=V1,V2,...` can vary, and the cartesian product of the
//! values given. Values use the command line's syntax and parsers (`--pcf`, `--vpls`,
//! `--reuse`, ...), so a sweep accepts exactly what a single run accepts. The frame-wide keys
//! (the cache's, the shadow map's size) are here; each effect declares its own in its folder
//! (`effects/<effect>/sweep.rs`) and the registry lists them.

use crate::config::antialias::AaMode;
use crate::config::parse::{
    parse_bias, parse_count, parse_ema_alpha, parse_epsilon, parse_fraction, parse_gate,
    parse_on_off, parse_pattern_count, AccumulateMode,
};
use crate::config::sweep_key::{value_names, SweepKey, Syntax};
use crate::config::{Accumulate, HistoryResample, Refresh};
use crate::error::{Error, Result};
use crate::renderer::RenderConfig;
use clap::ValueEnum;

/// Most combinations one sweep may expand to: far beyond any useful run, small enough that a
/// typo such as ten keys of ten values fails with a message instead of exhausting memory.
pub const MAX_COMBINATIONS: usize = 4096;

/// A key: one of `all_keys()`.
pub type Key = &'static SweepKey;

/// `temporal.accumulate`, applied after the other keys of a combination so that a bare `mean`
/// caps at the combination's own rotation limit, like `--accumulate mean` without `--mean-cap`.
pub const ACCUMULATE: SweepKey = SweepKey {
    name: "temporal.accumulate",
    syntax: Syntax::Text("gated[:SIGMAS]|confidence[:BIAS]|ema[:ALPHA]|mean[:CAP]"),
    description: "history merge, default parameter if none; mean alone caps at the rotation limit",
    set: |c, v| {
        c.temporal.accumulate = parse_accumulate(v, c.temporal.rotation_limit)?;
        Ok(())
    },
};

/// The frame-wide keys: the cache's, the shadow map's size, the antialiasing.
pub const FRAME_KEYS: &[SweepKey] = &[
    SweepKey {
        name: "temporal.reuse",
        syntax: Syntax::Text("on|off"),
        description: "reverse-reprojection reuse; off = no-reuse baseline (--reuse)",
        set: |c, v| {
            c.temporal.reuse = parse_on_off(v)?;
            Ok(())
        },
    },
    ACCUMULATE,
    SweepKey {
        name: "temporal.refresh",
        syntax: Syntax::Names(value_names::<Refresh>),
        description: "tiled refresh, one tile recomputed per frame; hard = the thesis's seams",
        set: |c, v| {
            c.temporal.refresh = Refresh::from_str(v, false)?;
            Ok(())
        },
    },
    SweepKey {
        name: "temporal.refresh_budget",
        syntax: Syntax::Text("PERCENT% or fraction in (0, 100]"),
        description: "refresh work per frame, share of a full frame's (--refresh-budget)",
        set: |c, v| {
            c.temporal.refresh_budget = parse_fraction(v)?;
            Ok(())
        },
    },
    SweepKey {
        name: "temporal.rotation_limit",
        syntax: Syntax::Text("integer 1..=2048"),
        description: "patterns per pixel before it counts as converged",
        set: |c, v| {
            c.temporal.rotation_limit = parse_pattern_count(v)?;
            Ok(())
        },
    },
    SweepKey {
        name: "temporal.epsilon",
        syntax: Syntax::Text("NUMBER|abs:NUMBER"),
        description: "disocclusion threshold: pixel footprints, or abs: world units",
        set: |c, v| {
            c.temporal.epsilon = parse_epsilon(v)?;
            Ok(())
        },
    },
    SweepKey {
        name: "temporal.resample",
        syntax: Syntax::Names(value_names::<HistoryResample>),
        description: "history read between texels under motion (--history-resample)",
        set: |c, v| {
            c.temporal.resample = HistoryResample::from_str(v, false)?;
            Ok(())
        },
    },
    SweepKey {
        name: "temporal.reaccumulate",
        syntax: Syntax::Text("on|off"),
        description: "histories re-accumulate when the camera stops (--reaccumulate)",
        set: |c, v| {
            c.temporal.reaccumulate = parse_on_off(v)?;
            Ok(())
        },
    },
    SweepKey {
        name: "rsm_size",
        syntax: Syntax::Text("integer 1..=16384"),
        description: "side of the (reflective) shadow map in texels (--rsm-size)",
        set: |c, v| {
            c.rsm_size = parse_count(v, 1, crate::renderer::MAX_SIZE)?;
            Ok(())
        },
    },
    SweepKey {
        name: "aa",
        syntax: Syntax::Names(value_names::<AaMode>),
        description: "antialiasing; ssaa16 renders 16 samples per pixel, the reference (--aa)",
        set: |c, v| {
            c.aa.mode = AaMode::from_str(v, false)?;
            Ok(())
        },
    },
];

/// Every key, in the order `help_table` lists them: the frame-wide ones, then each effect's
/// in registry order.
pub fn all_keys() -> Vec<Key> {
    FRAME_KEYS
        .iter()
        .chain(crate::effects::sweep_keys())
        .collect()
}

/// The key called `name` (trimmed), if there is one.
pub fn find_key(name: &str) -> Option<Key> {
    let name = name.trim();
    all_keys().into_iter().find(|k| k.name == name)
}

/// The key called `name`; an unknown name gets every valid key in the error.
pub fn parse_key(name: &str) -> Result<Key> {
    let name = name.trim();
    find_key(name).ok_or_else(|| {
        let known: Vec<&str> = all_keys().iter().map(|k| k.name).collect();
        Error::Config(format!(
            "unknown --vary key {name:?}; valid keys: {}",
            known.join(", ")
        ))
    })
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
    let key = parse_key(name)?;
    let values: Vec<String> = list.split(',').map(|v| v.trim().to_string()).collect();
    if values.iter().any(String::is_empty) {
        return Err(Error::Config(format!(
            "--vary {key}: empty value in {:?} (expected {})",
            list.trim(),
            key.syntax
        )));
    }
    for (i, v) in values.iter().enumerate() {
        check(key, v)?;
        if let Some(first) = values[..i].iter().find(|w| same_value(key, w, v)) {
            return Err(Error::Config(format!(
                "--vary {key}: {first:?} and {v:?} set the same value; give each once"
            )));
        }
    }
    Ok(Vary { key, values })
}

/// Set `key`'s field of `config` to `value`. Only the value's syntax and the command line's
/// range checks happen here; `RenderConfig::validate` is the caller's job, since a value may be
/// valid or not depending on the other fields (`indirect.vpls=all` needs a small `rsm_size`).
/// A rejected value leaves `config` as it was.
pub fn apply(config: &mut RenderConfig, key: Key, value: &str) -> Result<()> {
    let mut c = *config;
    (key.set)(&mut c, value.trim()).map_err(|why| invalid(key, value, &why))?;
    *config = c;
    Ok(())
}

fn invalid(key: Key, value: &str, why: &str) -> Error {
    Error::Config(format!(
        "--vary {key}: invalid value {value:?} ({why}); expected {}",
        key.syntax
    ))
}

/// Whether `value` is one of `key`'s values.
fn check(key: Key, value: &str) -> Result<()> {
    apply(&mut RenderConfig::default(), key, value)
}

/// Whether two values of `key` set the same configuration from every base: the default, and
/// the default with another rotation limit (a bare `mean`, capped at the limit, is not `mean:N`
/// for any one N).
fn same_value(key: Key, a: &str, b: &str) -> bool {
    let mut other = RenderConfig::default();
    other.temporal.rotation_limit += 1;
    [RenderConfig::default(), other].into_iter().all(|base| {
        let (mut x, mut y) = (base, base);
        apply(&mut x, key, a).is_ok() && apply(&mut y, key, b).is_ok() && x == y
    })
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
    order.sort_by_key(|&i| *varies[i].key == ACCUMULATE);
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
    let rows: Vec<[String; 3]> = all_keys()
        .iter()
        .map(|k| [k.name, &k.syntax.to_string(), k.description].map(str::to_string))
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

/// `MODE[:PARAMETER]`: the mode as `--accumulate` takes it, the parameter as `--gate`,
/// `--bias`, `--ema-alpha` or `--mean-cap` takes it; without one, the command line's default
/// (a bare `mean` caps at `rotation_limit`).
fn parse_accumulate(v: &str, rotation_limit: u32) -> std::result::Result<Accumulate, String> {
    let (mode, parameter) = match v.split_once(':') {
        Some((m, p)) => (m, Some(p)),
        None => (v, None),
    };
    let mode = AccumulateMode::from_str(mode, false)?;
    Ok(match (mode, parameter) {
        (AccumulateMode::Gated, None) => Accumulate::GATED,
        (AccumulateMode::Gated, Some(p)) => Accumulate::Gated {
            sigmas: parse_gate(p)?,
        },
        (AccumulateMode::Confidence, None) => Accumulate::CONFIDENCE,
        (AccumulateMode::Confidence, Some(p)) => Accumulate::Confidence {
            bias: parse_bias(p)?,
        },
        (AccumulateMode::Ema, p) => Accumulate::Ema {
            alpha: p.map_or(Ok(Accumulate::EMA_ALPHA), parse_ema_alpha)?,
        },
        (AccumulateMode::Mean, None) => Accumulate::Mean {
            cap: rotation_limit,
        },
        (AccumulateMode::Mean, Some(p)) => Accumulate::Mean {
            cap: parse_pattern_count(p)?,
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::pcf::PcfKernel;
    use crate::config::Epsilon;
    use std::fmt;

    fn err(r: Result<impl fmt::Debug>) -> String {
        r.expect_err("expected an error").to_string()
    }

    /// Sets the field a key should set, written out by hand.
    type SetByHand = fn(&mut RenderConfig);

    fn key(name: &str) -> Key {
        parse_key(name).unwrap()
    }

    #[test]
    fn each_frame_key_changes_exactly_its_field() {
        let base = RenderConfig::default();
        let cases: Vec<(&str, &str, SetByHand)> = vec![
            ("temporal.reuse", "off", |c| c.temporal.reuse = false),
            ("temporal.reaccumulate", "off", |c| {
                c.temporal.reaccumulate = false
            }),
            ("temporal.accumulate", "ema:0.25", |c| {
                c.temporal.accumulate = Accumulate::Ema { alpha: 0.25 }
            }),
            ("temporal.refresh", "hard", |c| {
                c.temporal.refresh = Refresh::Hard
            }),
            ("temporal.resample", "point", |c| {
                c.temporal.resample = HistoryResample::Point
            }),
            ("temporal.refresh_budget", "225%", |c| {
                c.temporal.refresh_budget = 2.25
            }),
            ("temporal.rotation_limit", "64", |c| {
                c.temporal.rotation_limit = 64
            }),
            ("temporal.epsilon", "abs:0.1", |c| {
                c.temporal.epsilon = Epsilon::Absolute { epsilon: 0.1 }
            }),
            ("rsm_size", "1024", |c| c.rsm_size = 1024),
            ("aa", "sraa", |c| c.aa.mode = AaMode::Sraa),
        ];
        assert_eq!(cases.len(), FRAME_KEYS.len(), "a key without a test");
        for (name, value, set) in cases {
            let key = key(name);
            let mut expected = base;
            set(&mut expected);
            assert_ne!(expected, base, "{key}={value} must differ from the default");
            let mut got = base;
            apply(&mut got, key, value).unwrap();
            assert_eq!(got, expected, "{key}={value}");
            assert_eq!(parse_key(key.name).unwrap(), key);
        }
    }

    #[test]
    fn accumulate_takes_the_command_line_modes_and_parameters() {
        let set = |v: &str| {
            let mut c = RenderConfig::default();
            c.temporal.rotation_limit = 20;
            apply(&mut c, &ACCUMULATE, v).map(|_| c.temporal.accumulate)
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
        apply(&mut c, key("pcf"), "disc:16").unwrap();
        assert_eq!(c.pcf.kernel, PcfKernel::Disc { samples: 16 });
    }

    #[test]
    fn unknown_key_lists_every_key() {
        let e = err(parse_vary("ao.sample=1,2"));
        assert!(e.contains("\"ao.sample\""), "{e}");
        for k in all_keys() {
            assert!(e.contains(k.name), "{e} lacks {k}");
        }
        let table = help_table();
        for k in all_keys() {
            assert!(
                table.contains(k.name) && table.contains(&k.syntax.to_string()),
                "{table}"
            );
        }
        assert_eq!(table.lines().count(), all_keys().len() + 1);
    }

    #[test]
    fn bad_values_are_rejected_with_the_syntax() {
        for (s, key, value) in [
            ("ao.samples=8,0", "ao.samples", "0"),
            ("ao.samples=x", "ao.samples", "x"),
            (
                "ao.estimator=thesis,no-such-estimator",
                "ao.estimator",
                "no-such-estimator",
            ),
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
            let syntax = parse_key(key).unwrap().syntax.to_string();
            assert!(
                e.contains(key) && e.contains(&format!("{value:?}")) && e.contains(&syntax),
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
        assert_eq!(v.key, key("ao.samples"));
        assert_eq!(v.values, ["8", "16"]);
        let mut c = RenderConfig::default();
        assert!(apply(&mut c, key("ao.samples"), "-1").is_err());
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
