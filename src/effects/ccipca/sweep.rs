//! CCIPCA's keys for `ssgi sweep --vary` and `table chang-flicker --set` (the registry hands
//! them to the sweep). Each mirrors its command-line option's range.

use super::config::{CcipcaConfig, CcipcaOrthogonalize, CcipcaProject, CcipcaWeighting};
use crate::config::parse::parse_count;
use crate::config::sweep_key::{value_names, SweepKey, Syntax};
use clap::ValueEnum;

pub const SWEEP_KEYS: &[SweepKey] = &[
    SweepKey {
        name: "ccipca.bases",
        syntax: Syntax::Text("integer 1..=8"),
        description: "CCIPCA basis images (--bases)",
        set: |c, v| {
            c.ccipca.bases = parse_count(v, 1, CcipcaConfig::MAX_BASES)?;
            Ok(())
        },
    },
    SweepKey {
        name: "ccipca.weighting",
        syntax: Syntax::Names(value_names::<CcipcaWeighting>),
        description: "whose sample count sets a CCIPCA step (--ccipca-weighting)",
        set: |c, v| {
            c.ccipca.weighting = CcipcaWeighting::from_str(v, false)?;
            Ok(())
        },
    },
    SweepKey {
        name: "ccipca.project",
        syntax: Syntax::Names(value_names::<CcipcaProject>),
        description: "project each frame on the bases before or after updating them \
                      (--ccipca-project)",
        set: |c, v| {
            c.ccipca.project = CcipcaProject::from_str(v, false)?;
            Ok(())
        },
    },
    SweepKey {
        name: "ccipca.basis_filter",
        syntax: Syntax::Text("integer 0..=8"),
        description: "CCIPCA basis filter radius in pixels, 0 = off (--ccipca-basis-filter)",
        set: |c, v| {
            c.ccipca.basis_filter = parse_count(v, 0, CcipcaConfig::MAX_BASIS_FILTER)?;
            Ok(())
        },
    },
    SweepKey {
        name: "ccipca.orthogonalize",
        syntax: Syntax::Names(value_names::<CcipcaOrthogonalize>),
        description: "when CCIPCA orthogonalizes its bases (--ccipca-orthogonalize)",
        set: |c, v| {
            c.ccipca.orthogonalize = CcipcaOrthogonalize::from_str(v, false)?;
            Ok(())
        },
    },
    SweepKey {
        name: "ccipca.new_pixel_vpls",
        syntax: Syntax::Text("integer 0..=16384"),
        description: "VPLs a pixel new to the view gathers, 0 = --vpls \
                      (--ccipca-new-pixel-vpls)",
        set: |c, v| {
            c.ccipca.new_pixel_vpls = parse_count(v, 0, 16384)?;
            Ok(())
        },
    },
    SweepKey {
        name: "ccipca.max_age",
        syntax: Syntax::Text("integer 1..=1048576"),
        description: "frames after which a CCIPCA step stops shrinking (--ccipca-max-age)",
        set: |c, v| {
            c.ccipca.max_age = parse_count(v, 1, 1 << 20)?;
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
            ("ccipca.bases", "5", |c| c.ccipca.bases = 5),
            ("ccipca.weighting", "uniform", |c| {
                c.ccipca.weighting = CcipcaWeighting::Uniform
            }),
            ("ccipca.project", "after", |c| {
                c.ccipca.project = CcipcaProject::After
            }),
            ("ccipca.basis_filter", "0", |c| c.ccipca.basis_filter = 0),
            ("ccipca.orthogonalize", "always", |c| {
                c.ccipca.orthogonalize = CcipcaOrthogonalize::Always
            }),
            ("ccipca.new_pixel_vpls", "128", |c| {
                c.ccipca.new_pixel_vpls = 128
            }),
            ("ccipca.max_age", "64", |c| c.ccipca.max_age = 64),
        ];
        assert_each_key_sets_its_field(SWEEP_KEYS, cases);
    }
}
