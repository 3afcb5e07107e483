//! SSAO's configuration (Lin 2013 eqs 6-8, Mittring's and Szentandrasi's estimators): its
//! estimator, samples, radius, attenuation, nearest step, patterns and far-tap position
//! levels, and their validation. Plain data: the bottom layer's `RenderConfig` holds it, so it
//! uses nothing above `error`.

use crate::error::{Error, Result};
use serde::Serialize;

/// The SSAO estimator. Its names (`--ao`, the sweep key `ao.estimator`, `table ao`'s rows, the
/// viewer's choices) come from this enum; its code, the SSAO passes' specialization constant,
/// from shaders/include/shared_constants.glsl.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
#[repr(u32)]
pub enum AoEstimator {
    /// Lin 2013 eqs 6-8: normal-weighted, attenuated, log-spaced screen-space steps.
    Thesis = crate::shaders::AO_THESIS,
    /// Mittring 2007: depth comparisons of points in a sphere (flat surfaces come out grey).
    Crytek = crate::shaders::AO_CRYTEK,
    /// Szentandrasi section 3.1: Halton points in the normal's hemisphere, back-projected; the
    /// fraction behind the visible surface.
    Szentandrasi = crate::shaders::AO_SZENTANDRASI,
    /// Jimenez et al. 2016 (ground-truth AO, as Intel's XeGTAO): per slice through the view
    /// vector, the two horizons within the radius and the cosine-weighted visibility between
    /// them in closed form; `--ao-samples` taps split into slices of 2 x `--ao-steps`.
    Gtao = crate::shaders::AO_GTAO,
}

impl AoEstimator {
    /// The estimating passes' specialization constant `AO_ESTIMATOR` (ao.glsl): the AO_*
    /// code of shaders/include/shared_constants.glsl, the variant's discriminant.
    pub fn code(self) -> u32 {
        self as u32
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct AoConfig {
    pub estimator: AoEstimator,
    /// Samples per pattern (thesis: directions x steps; 32 = 8 x 4).
    pub samples: u32,
    /// World-space sampling radius as a fraction of the scene's bounding radius (scale-free).
    pub radius: f32,
    /// Attenuation D(d) = 1 + a d + b d^2 (eq 7), d in units of the sampling radius.
    pub attenuation: [f32; 2],
    /// Nearest sample distance in pixels (eq 8's `near`).
    pub near_px: f32,
    /// Patterns evaluated at once (1 in normal runs; references use many).
    pub patterns: u32,
    /// Far taps read point-sampled levels of the G-buffer position, up to this level (0: every
    /// tap reads the full-resolution G-buffer, the estimator as published).
    pub position_mips: u32,
    /// GTAO: horizon-search steps on each side of a slice (slices = samples / (2 steps)). 8 by
    /// default, two slices of the default 32 samples: fewer steps miss horizons near the
    /// radius, one slice per pattern leaves the cache further from its converged value, and
    /// 16 steps help the Table 4.1 scenes but hurt the walkthroughs, so it is a choice per
    /// scene (figures: docs/results/DECISIONS.md, "GTAO steps per side").
    pub steps: u32,
    /// GTAO with the cache: under camera motion each fresh pattern is denoised over its 5x5
    /// neighbours that estimated one the same frame (gtao_denoise.glsl's edge-aware weights)
    /// before it enters the history (`shaders/ao/gtao_moving.comp`). A still camera merges raw
    /// patterns, so the converged value is each pixel's own mean either way.
    pub moving_denoise: bool,
}

impl Default for AoConfig {
    fn default() -> Self {
        Self {
            estimator: AoEstimator::Thesis,
            samples: 32,
            radius: 0.25,
            attenuation: [0.0, 1.0],
            near_px: 1.5,
            patterns: 1,
            position_mips: 0,
            steps: 8,
            moving_denoise: true,
        }
    }
}

impl AoConfig {
    /// Most point-sampled position levels (`ao_position_chain.comp` writes levels 1-3).
    pub const MAX_POSITION_MIPS: u32 = 3;

    /// Directions and steps per direction of the thesis estimator for `samples`.
    pub fn directions_steps(&self) -> (u32, u32) {
        let steps = if self.samples >= 16 { 4 } else { 2 };
        ((self.samples / steps).max(1), steps)
    }

    /// Most GTAO steps per side.
    pub const MAX_STEPS: u32 = 256;

    /// GTAO's slices and steps per side for `samples` taps: at least one slice, each of
    /// 2 x `steps` taps.
    pub fn slices_steps(&self) -> (u32, u32) {
        ((self.samples / (2 * self.steps.max(1))).max(1), self.steps)
    }

    /// Its rules: counts, radius, attenuation and nearest step within what the shaders take,
    /// a clear error for each, never a clamp.
    pub fn validate(&self) -> Result<()> {
        let bad = |m: String| Err(Error::Config(m));
        let ao = self;
        if !(1..=4096).contains(&ao.samples) {
            return bad(format!("AO samples {} outside 1..=4096", ao.samples));
        }
        if !(1..=AoConfig::MAX_STEPS).contains(&ao.steps) {
            return bad(format!(
                "GTAO steps per side {} outside 1..={}",
                ao.steps,
                AoConfig::MAX_STEPS
            ));
        }
        if ao.position_mips > AoConfig::MAX_POSITION_MIPS {
            return bad(format!(
                "AO position levels {} outside 0..={}",
                ao.position_mips,
                AoConfig::MAX_POSITION_MIPS
            ));
        }
        if !(1..=1024).contains(&ao.patterns) {
            return bad(format!("AO patterns {} outside 1..=1024", ao.patterns));
        }
        if !(ao.radius.is_finite() && ao.radius > 0.0 && ao.radius <= 10.0) {
            return bad(format!(
                "AO radius {} must be in (0, 10] scene radii",
                ao.radius
            ));
        }
        if ao.attenuation.iter().any(|c| !c.is_finite() || *c < 0.0) {
            return bad("AO attenuation coefficients must be finite and >= 0".into());
        }
        // A divisor in the step spacing (eq 8): positive, and well inside the image.
        if !(ao.near_px.is_finite() && ao.near_px > 0.0 && ao.near_px <= 64.0) {
            return bad(format!(
                "AO nearest step {} px must be in (0, 64]",
                ao.near_px
            ));
        }
        Ok(())
    }
}
