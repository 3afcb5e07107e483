//! SRAA's weights (Chajdas et al. 2011's eq 1, Chiu et al.'s shadow term) and their
//! validation. Plain data: the bottom layer's `RenderConfig` holds it, so it uses nothing above
//! `error`.

use crate::error::{Error, Result};
use serde::Serialize;

#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SraaConfig {
    /// Eq 1's depth scale, on the relative difference of the distances from the eye (the
    /// paper's 10: a neighbour 10% nearer or farther weighs 1/e).
    pub sigma_z: f32,
    /// Eq 1's normal scale, on 1 - sat(n_j . n_i) (the paper's 0.25).
    pub sigma_n: f32,
    /// The shadow term's scale on the difference of the hard shadow tests (0 or 1) with
    /// `sraa-shadow`: 4 leaves exp(-16) across a shadow edge. The report gives no value (its
    /// eq 2 is not in the text); ours.
    pub sigma_shadow: f32,
}

impl Default for SraaConfig {
    fn default() -> Self {
        Self {
            sigma_z: 10.0,
            sigma_n: 0.25,
            sigma_shadow: 4.0,
        }
    }
}

impl SraaConfig {
    pub fn validate(&self) -> Result<()> {
        for (what, v) in [
            ("SRAA depth scale", self.sigma_z),
            ("SRAA normal scale", self.sigma_n),
            ("SRAA shadow scale", self.sigma_shadow),
        ] {
            // Past 1e4 exp(-(s x)^2) underflows for any difference a float resolves.
            if !(v.is_finite() && (0.0..=1e4).contains(&v)) {
                return Err(Error::Config(format!("{what} {v} must be in [0, 10000]")));
            }
        }
        Ok(())
    }
}
