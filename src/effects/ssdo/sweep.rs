//! SSDO's keys for `ssgi sweep --vary` (the registry hands them to the sweep).

use super::config::{parse_bilateral, parse_ssdo_scale, SsdoConfig, SsdoForm};
use crate::config::parse::{parse_count, parse_radius};
use crate::config::sweep_key::{value_names, SweepKey, Syntax};
use clap::ValueEnum;

pub const SWEEP_KEYS: &[SweepKey] = &[
    SweepKey {
        name: "ssdo.form",
        syntax: Syntax::Names(value_names::<SsdoForm>),
        description: "SSDO in one pass, Ritschel's two, or SSAO on its pipeline (--ssdo)",
        set: |c, v| {
            c.ssdo.form = SsdoForm::from_str(v, false)?;
            Ok(())
        },
    },
    SweepKey {
        name: "ssdo.samples",
        syntax: Syntax::Text("integer 1..=4096"),
        description: "SSDO hemisphere samples per pixel (--ssdo-samples)",
        set: |c, v| {
            c.ssdo.samples = parse_count(v, 1, SsdoConfig::MAX_SAMPLES)?;
            Ok(())
        },
    },
    SweepKey {
        name: "ssdo.radius",
        syntax: Syntax::Text("number in (0, 10]"),
        description: "SSDO hemisphere radius, fraction of the scene's bounding radius",
        set: |c, v| {
            c.ssdo.radius = parse_radius(v)?;
            Ok(())
        },
    },
    SweepKey {
        name: "ssdo.filter",
        syntax: Syntax::Text("odd integer 1..=31|off"),
        description: "SSDO's separable bilateral filter side (--bilateral)",
        set: |c, v| {
            c.ssdo.filter = parse_bilateral(v)?;
            Ok(())
        },
    },
    SweepKey {
        name: "ssdo.scale",
        syntax: Syntax::Text("1|0.5"),
        description: "SSDO's resolution, upsampled when half (--ssdo-scale)",
        set: |c, v| {
            c.ssdo.scale = parse_ssdo_scale(v)?;
            Ok(())
        },
    },
];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::sweep_key::{assert_each_key_sets_its_field, SetByHand};

    #[test]
    fn each_key_changes_exactly_its_field() {
        let cases: Vec<(&str, &str, SetByHand)> = vec![
            ("ssdo.form", "two-step", |c| c.ssdo.form = SsdoForm::TwoStep),
            ("ssdo.samples", "50", |c| c.ssdo.samples = 50),
            ("ssdo.radius", "0.1", |c| c.ssdo.radius = 0.1),
            ("ssdo.filter", "off", |c| c.ssdo.filter = 0),
            ("ssdo.scale", "0.5", |c| c.ssdo.scale = 2),
        ];
        assert_each_key_sets_its_field(SWEEP_KEYS, cases);
    }
}
