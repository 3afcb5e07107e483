//! The direct light's key for `ssgi sweep --vary`: its shadow filter.

use crate::config::pcf::Pcf;
use crate::config::sweep_key::SweepKey;

pub const SWEEP_KEYS: &[SweepKey] = &[SweepKey {
    name: "pcf",
    syntax: "hard|9|SQUARE (25, 49, ...)|disc:N",
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
    use crate::config::RenderConfig;

    /// Sets the field a key should set, written out by hand.
    type SetByHand = fn(&mut RenderConfig);

    #[test]
    fn each_key_changes_exactly_its_field() {
        let base = RenderConfig::default();
        let cases: Vec<(&str, &str, SetByHand)> = vec![("pcf", "9", |c| c.pcf = Pcf::NINE)];
        assert_eq!(cases.len(), SWEEP_KEYS.len(), "a key without a test");
        for (key, (name, value, by_hand)) in SWEEP_KEYS.iter().zip(cases) {
            assert_eq!(key.name, name, "cases in the keys' order");
            let mut expected = base;
            by_hand(&mut expected);
            assert_ne!(
                expected, base,
                "{name}={value} must differ from the default"
            );
            let mut got = base;
            (key.set)(&mut got, value).unwrap();
            assert_eq!(got, expected, "{name}={value}");
        }
    }
}
