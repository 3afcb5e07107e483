//! Antialiasing settings: none, subpixel reconstruction (SRAA: Chajdas et al. 2011; Chiu et
//! al.'s shadow-aware weights), or 16x supersampling (the reference).

use crate::error::{Error, Result};
use serde::Serialize;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum AaMode {
    /// One sample per pixel, at its centre.
    None,
    /// Shade once per pixel, sample geometry at 4 subpixels (rotated grid), rebuild each
    /// subpixel's shading with eq 1's depth and normal weights, box-filter the four.
    Sraa,
    /// SRAA with a hard shadow-map test at every sample in the weights (the report's 3.2).
    SraaShadow,
    /// Render at 4x width and height (16 samples per pixel) and box-filter 4x4: the reference.
    Ssaa16,
}

impl AaMode {
    /// Whether the mode renders SRAA's subpixel geometry and reconstruction.
    pub fn subpixel(self) -> bool {
        matches!(self, AaMode::Sraa | AaMode::SraaShadow)
    }

    /// Render size per output pixel along each axis.
    pub fn supersampling(self) -> u32 {
        if self == AaMode::Ssaa16 {
            4
        } else {
            1
        }
    }

    /// Whether the composite writes a display-linear image for an antialiasing pass.
    pub fn resolves(self) -> bool {
        self != AaMode::None
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct AaConfig {
    pub mode: AaMode,
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

impl Default for AaConfig {
    fn default() -> Self {
        Self {
            mode: AaMode::None,
            sigma_z: 10.0,
            sigma_n: 0.25,
            sigma_shadow: 4.0,
        }
    }
}

impl AaConfig {
    /// The shadow term's scale the shaders get: 0 turns the term off.
    pub fn shadow_scale(&self) -> f32 {
        if self.mode == AaMode::SraaShadow {
            self.sigma_shadow
        } else {
            0.0
        }
    }

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
