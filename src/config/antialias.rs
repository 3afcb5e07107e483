//! Antialiasing settings: none, subpixel reconstruction (SRAA: Chajdas et al. 2011; Chiu et
//! al.'s shadow-aware weights), or 16x supersampling (the reference).

use crate::error::Result;
use crate::post::sraa::config::SraaConfig;
use serde::Serialize;

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum AaMode {
    /// One sample per pixel, at its centre.
    #[default]
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

#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct AaConfig {
    pub mode: AaMode,
    /// SRAA's weights (with `sraa` and `sraa-shadow`).
    pub sraa: SraaConfig,
}

impl AaConfig {
    /// The shadow term's scale the shaders get: 0 turns the term off.
    pub fn shadow_scale(&self) -> f32 {
        if self.mode == AaMode::SraaShadow {
            self.sraa.sigma_shadow
        } else {
            0.0
        }
    }

    pub fn validate(&self) -> Result<()> {
        self.sraa.validate()
    }
}
