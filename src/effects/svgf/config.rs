//! SVGF's configuration (Schied et al. 2017, `--indirect-filter svgf`): the temporal
//! accumulation's smallest weights of a new sample and the a-trous wavelet's iterations and
//! edge-stopping parameters, with the article's values as defaults, and their validation. Plain
//! data: the bottom layer's `RenderConfig` holds it, so it uses nothing above `error`.

use crate::error::{Error, Result};
use serde::Serialize;

/// How the temporal accumulation reads last frame's colour and moments at a pixel's surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum SvgfHistory {
    /// The default: last frame's nearest texel, where it holds the surface (eq 3 and the
    /// facing test), as CCIPCA's warp. Under motion it keeps the history sharp: on the
    /// chang-flicker table's moving camera the bilinear tap's error against the exact gather
    /// is 1.01-1.31x its own from 3 VPLs on (docs/results, lavapipe-svgf-bilinear-2026-12-07).
    Nearest,
    /// The article's: a bilinear tap whose four texels are each tested and renormalised over
    /// those that hold the surface, else the equal mean of the 3x3 block's that do. Fewer
    /// restarts at thin geometry, but each frame blends neighbours again, so a long history
    /// blurs; better only at 1 VPL (0.92-0.98x).
    Bilinear,
}

impl SvgfHistory {
    /// The shader's code (its push constant `bilinear`): SVGF_HISTORY_* of
    /// shared_constants.glsl.
    pub fn code(self) -> u32 {
        match self {
            SvgfHistory::Nearest => crate::shaders::SVGF_HISTORY_NEAREST,
            SvgfHistory::Bilinear => crate::shaders::SVGF_HISTORY_BILINEAR,
        }
    }
}

/// Spatiotemporal variance-guided filtering of the noisy indirect light.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SvgfConfig {
    /// A-trous iterations (the article: 5, a 61x61 footprint); the i-th spaces its 5x5 taps
    /// 2^i pixels apart. 0 = temporal accumulation alone.
    pub iterations: u32,
    /// Smallest weight of a new sample in the colour's running mean (the article's alpha,
    /// 0.2): until 1/alpha samples are integrated the mean weighs each alike.
    pub alpha: f32,
    /// The same for the luminance moments (the article: 0.2).
    pub alpha_moments: f32,
    /// The smallest weight of both once the lighting has held still for `alpha`'s settle
    /// time (`SvgfConfig::lit_settle_frames`): the article's 0.2 lets a changed light through
    /// within about 18 frames, but the diffuse indirect light of a still light does not change
    /// when only the camera moves (the reprojection follows each surface). The renderer knows
    /// each frame whether the light or an object moved (`FrameInfo`); the first such frame
    /// restores `alpha`. At or above `alpha` it changes nothing: the default, 0.2, is the
    /// article's accumulation. 0.05 lowers the moving camera's error at 1-3 VPLs per pixel
    /// (0.104 -> 0.067 at 1) but raises it from 10 and the still view's from 10 (0.065 ->
    /// 0.092 at 64): the history is the first a-trous iteration's output (the article's
    /// feedback), so a longer memory compounds that blur (docs/results,
    /// lavapipe-svgf-alpha-still-2026-12-07).
    pub alpha_still: f32,
    /// How last frame's values are read at the pixel's surface.
    pub history: SvgfHistory,
    /// Luminance edge-stopping: sigma_l, in standard deviations of the (3x3-prefiltered)
    /// variance (the article: 4).
    pub sigma_luminance: f32,
    /// Normal edge-stopping: the exponent sigma_n of max(0, n . n_q) (the article: 128).
    pub sigma_normal: f32,
    /// Depth edge-stopping: sigma_z, in multiples of the depth change the pixel's own gradient
    /// predicts at the tap (the article: 1).
    pub sigma_depth: f32,
}

impl SvgfConfig {
    /// Most a-trous iterations: the 10th spaces its taps 512 pixels apart, past any useful
    /// footprint.
    pub const MAX_ITERATIONS: u32 = 10;

    /// Its rules, a clear error for each, never a clamp.
    pub fn validate(&self) -> Result<()> {
        let bad = |m: String| Err(Error::Config(m));
        if self.iterations > SvgfConfig::MAX_ITERATIONS {
            return bad(format!(
                "{} SVGF a-trous iterations is more than {}",
                self.iterations,
                SvgfConfig::MAX_ITERATIONS
            ));
        }
        for (what, v) in [
            ("--svgf-alpha", self.alpha),
            ("--svgf-alpha-moments", self.alpha_moments),
            ("--svgf-alpha-still", self.alpha_still),
        ] {
            if !(v > 0.0 && v <= 1.0) {
                return bad(format!(
                    "{what} {v}: a new sample's weight must be in (0, 1]"
                ));
            }
        }
        for (what, v) in [
            ("--svgf-sigma-luminance", self.sigma_luminance),
            ("--svgf-sigma-normal", self.sigma_normal),
            ("--svgf-sigma-depth", self.sigma_depth),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return bad(format!("{what} {v}: must be finite and >= 0"));
            }
        }
        Ok(())
    }

    /// Frames after a restart until a pixel's running mean forgets its first sample to within
    /// e^-4 (2%): (1 - alpha)^n <= e^-4; with a smaller `alpha_still`, then until the still
    /// lighting's mean forgets the samples `alpha` weighed. Until then the output still
    /// settles with unchanged inputs.
    pub fn settle_frames(&self) -> u32 {
        let (colour, moments) = self.still_alphas();
        let still = colour.min(moments);
        let lit = self.lit_settle_frames();
        if still < self.alpha.min(self.alpha_moments) {
            lit + memory_frames(still)
        } else {
            lit
        }
    }

    /// Frames at `alpha` after a change of the lighting until its old value is forgotten to
    /// within e^-4; after them `alpha_still` applies.
    pub fn lit_settle_frames(&self) -> u32 {
        memory_frames(self.alpha.min(self.alpha_moments))
    }

    /// The colour's and the moments' smallest weights once the lighting has held still.
    pub fn still_alphas(&self) -> (f32, f32) {
        (
            self.alpha.min(self.alpha_still),
            self.alpha_moments.min(self.alpha_still),
        )
    }
}

/// Frames until a running mean of smallest weight `alpha` forgets a sample to within e^-4:
/// (1 - alpha)^n <= e^-4.
fn memory_frames(alpha: f32) -> u32 {
    let a = alpha.clamp(1e-6, 1.0) as f64;
    if a >= 1.0 {
        return 1;
    }
    (4.0 / -(1.0 - a).ln()).ceil().min(1e6) as u32
}

/// A new sample's weight in a running mean: a number in (0, 1] (`--svgf-alpha`, the sweep's
/// `svgf.alpha`).
pub fn parse_weight(s: &str) -> std::result::Result<f32, String> {
    match s.parse::<f32>() {
        Ok(a) if a > 0.0 && a <= 1.0 => Ok(a),
        _ => Err(format!("not a weight in (0, 1]: {s:?}")),
    }
}

/// An edge-stopping parameter: a finite number >= 0 (0 turns the term into a hard test).
pub fn parse_sigma(s: &str) -> std::result::Result<f32, String> {
    match s.parse::<f32>() {
        Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
        _ => Err(format!("not a finite number >= 0: {s:?}")),
    }
}

impl Default for SvgfConfig {
    fn default() -> Self {
        Self {
            iterations: 5,
            alpha: 0.2,
            alpha_moments: 0.2,
            alpha_still: 0.2,
            history: SvgfHistory::Nearest,
            sigma_luminance: 4.0,
            sigma_normal: 128.0,
            sigma_depth: 1.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_values_are_refused_with_their_option() {
        let c = SvgfConfig::default();
        assert!(c.validate().is_ok());
        for (bad, option) in [
            (
                SvgfConfig {
                    iterations: 11,
                    ..c
                },
                "iterations",
            ),
            (SvgfConfig { alpha: 0.0, ..c }, "--svgf-alpha"),
            (
                SvgfConfig {
                    alpha_moments: f32::NAN,
                    ..c
                },
                "--svgf-alpha-moments",
            ),
            (
                SvgfConfig {
                    sigma_normal: -1.0,
                    ..c
                },
                "--svgf-sigma-normal",
            ),
            (
                SvgfConfig {
                    sigma_depth: f32::INFINITY,
                    ..c
                },
                "--svgf-sigma-depth",
            ),
        ] {
            let e = bad.validate().unwrap_err().to_string();
            assert!(e.contains(option), "{e}");
        }
    }

    #[test]
    fn the_mean_settles_after_its_memory() {
        // (1 - 0.2)^18 = 0.018 <= e^-4 = 0.0183 < 0.8^17; (1 - 0.05)^78 = 0.0183 <= e^-4.
        let c = SvgfConfig::default();
        assert_eq!(c.lit_settle_frames(), 18);
        assert_eq!(c.settle_frames(), 18);
        let longer = SvgfConfig {
            alpha_still: 0.05,
            ..c
        };
        assert_eq!(longer.settle_frames(), 18 + 78);
        let one = SvgfConfig {
            alpha: 1.0,
            alpha_moments: 1.0,
            alpha_still: 1.0,
            ..c
        };
        assert_eq!(one.settle_frames(), 1);
    }
}
