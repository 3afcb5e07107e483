//! The direct light's key for `ssgi sweep --vary`: its shadow filter.

use crate::config::pcf::Pcf;
use crate::config::sweep_key::{SweepKey, Syntax};

pub const SWEEP_KEYS: &[SweepKey] = &[SweepKey {
    name: "pcf",
    syntax: Syntax::Text("hard|9|SQUARE (25, 49, ...)|disc:N"),
    description: "shadow filtering kernel (--pcf)",
    set: |c, v| {
        c.pcf = Pcf::parse(v)?;
        Ok(())
    },
}];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::pcf::Pcf;
    use crate::config::sweep_key::{assert_each_key_sets_its_field, SetByHand};

    #[test]
    fn each_key_changes_exactly_its_field() {
        let cases: Vec<(&str, &str, SetByHand)> = vec![("pcf", "9", |c| c.pcf = Pcf::NINE)];
        assert_each_key_sets_its_field(SWEEP_KEYS, cases);
    }
}
