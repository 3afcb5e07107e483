//! SSDO's configuration (Szentandrasi sections 3-4): its form, samples, radius, filter and
//! resolution, their validation and the value parsers of its options. Plain data: the bottom
//! layer's `RenderConfig` holds it, so it uses nothing above `error`.

use crate::error::{Error, Result};
use serde::Serialize;

/// Which of SSDO's forms runs (Szentandrasi sections 3.2 and 4.1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum SsdoForm {
    /// Section 4.1: the modulation factor and the bounce in one pass; the bounce's senders are
    /// lit as the frame is without SSDO, the bounce darkened by the modulation factor.
    OneStep,
    /// Ritschel et al.'s original: a directional-occlusion pass, then a bounce pass reading it.
    TwoStep,
    /// Section 3.1's SSAO on SSDO's pipeline (same Halton samples, pre-pass, filter, half
    /// resolution and upsampling): the unoccluded fraction, which darkens the ambient light
    /// only, and no bounce. The SSAO rows of the paper's Table 1.
    Ssao,
}

/// Szentandrasi's pre-pass (sections 4.2-4.3): each block of `scale` x `scale` pixels takes
/// `min` samples plus one Halton period (10) for each threshold its change measure exceeds
/// (shaders/ssdo/ssdo_samples.comp).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct AdaptiveSamples {
    pub min: u32,
    pub scale: u32,
    /// Ascending; (max - min) / 10 of them.
    pub thresholds: [f32; 4],
    pub threshold_count: u32,
}

impl AdaptiveSamples {
    /// The paper's Figure 6 and Table 1: 20 to 50 samples, a pre-pass at a quarter resolution.
    pub const PAPER: AdaptiveSamples = AdaptiveSamples {
        min: 20,
        scale: 4,
        thresholds: [0.02, 0.1, 0.3, 0.0],
        threshold_count: 3,
    };
    /// Default thresholds, the first (max - min) / 10 of these: a crease of 11 degrees
    /// (1 - cos = 0.02) or a step of 2% of the block's size takes one period more, 26 degrees
    /// or 10% two, 46 degrees or 30% three, 66 degrees or 60% four.
    pub const DEFAULT_THRESHOLDS: [f32; 4] = [0.02, 0.1, 0.3, 0.6];

    /// `min` to `max` samples (multiples of the period) with the default thresholds.
    pub fn range(min: u32, max: u32, scale: u32) -> AdaptiveSamples {
        let count = (max.saturating_sub(min) / SsdoConfig::HALTON_PERIOD).min(4);
        let mut thresholds = [0.0; 4];
        thresholds[..count as usize].copy_from_slice(&Self::DEFAULT_THRESHOLDS[..count as usize]);
        AdaptiveSamples {
            min,
            scale,
            thresholds,
            threshold_count: count,
        }
    }

    /// Most samples a block takes.
    pub fn max(&self) -> u32 {
        self.min + SsdoConfig::HALTON_PERIOD * self.threshold_count
    }

    pub fn thresholds(&self) -> &[f32] {
        &self.thresholds[..self.threshold_count.min(4) as usize]
    }
}

/// Screen-space directional occlusion (Szentandrasi section 3.2, Ritschel et al. 2009).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SsdoConfig {
    pub form: SsdoForm,
    /// Hemisphere samples per pixel (K): whole Halton periods of 10 keep them evenly spread.
    /// With `adaptive`, the most a block takes.
    pub samples: u32,
    /// Per-block sample counts from the pre-pass instead of `samples`.
    pub adaptive: Option<AdaptiveSamples>,
    /// Hemisphere radius r_max as a fraction of the scene's bounding radius (scale-free).
    pub radius: f32,
    /// Side of the separable bilateral filter (odd), 0 = off.
    pub filter: u32,
    /// Resolution divisor of the SSDO passes and the filter (1, or 2: half resolution, joint
    /// bilateral upsampling to the frame).
    pub scale: u32,
}

impl Default for SsdoConfig {
    fn default() -> Self {
        Self {
            form: SsdoForm::OneStep,
            samples: 20,
            adaptive: None,
            radius: 0.25,
            filter: 11,
            scale: 1,
        }
    }
}

impl SsdoConfig {
    /// Largest filter side: 31 taps per pass.
    pub const MAX_FILTER: u32 = 31;
    /// Most samples per pixel (one invocation loops over them; llvmpipe caps loops near 2^16).
    pub const MAX_SAMPLES: u32 = 4096;
    /// Eq 8's period of the Halton bases 2 and 5 (shaders/include/halton.glsl).
    pub const HALTON_PERIOD: u32 = 10;
    /// Largest pre-pass resolution divisor.
    pub const MAX_PREPASS_SCALE: u32 = 64;

    /// The configuration's SSDO rules: its counts, radius, filter and divisor, and what it
    /// cannot be combined with (`enabled`: SSDO runs; `ao_enabled`: SSAO runs too; `reuse`:
    /// the cache is on). A clear error for each, never a clamp.
    pub fn validate(&self, enabled: bool, ao_enabled: bool, reuse: bool) -> Result<()> {
        let bad = |m: String| Err(Error::Config(m));
        let ssdo = self;
        if enabled && ao_enabled {
            return bad(
                "ssdo and ao both darken the ambient light (SSDO's modulation factor is a \
                 directional AO): enable one of them"
                    .into(),
            );
        }
        if !(1..=SsdoConfig::MAX_SAMPLES).contains(&ssdo.samples) {
            return bad(format!(
                "SSDO samples {} outside 1..={}",
                ssdo.samples,
                SsdoConfig::MAX_SAMPLES
            ));
        }
        if let Some(a) = &ssdo.adaptive {
            if a.min == 0 || !a.min.is_multiple_of(SsdoConfig::HALTON_PERIOD) {
                return bad(format!(
                    "adaptive SSDO: the fewest samples ({}) must be a positive multiple of the \
                     Halton period {}",
                    a.min,
                    SsdoConfig::HALTON_PERIOD
                ));
            }
            if !(1..=4).contains(&a.threshold_count) || a.max() > SsdoConfig::MAX_SAMPLES {
                return bad(format!(
                    "adaptive SSDO takes 1 to 4 more periods than its minimum (got {}), at most \
                     {} samples",
                    a.threshold_count,
                    SsdoConfig::MAX_SAMPLES
                ));
            }
            if a.max() != ssdo.samples {
                return bad(format!(
                    "adaptive SSDO from {} to {} samples takes {} thresholds, not {}",
                    a.min,
                    ssdo.samples,
                    ssdo.samples.saturating_sub(a.min) / SsdoConfig::HALTON_PERIOD,
                    a.threshold_count
                ));
            }
            let t = a.thresholds();
            if t.iter().any(|v| !v.is_finite() || *v < 0.0) || t.windows(2).any(|w| w[0] >= w[1]) {
                return bad(format!(
                    "adaptive SSDO thresholds {t:?} must be finite, >= 0 and ascending"
                ));
            }
            if !(1..=SsdoConfig::MAX_PREPASS_SCALE).contains(&a.scale) {
                return bad(format!(
                    "SSDO pre-pass scale {} outside 1..={}",
                    a.scale,
                    SsdoConfig::MAX_PREPASS_SCALE
                ));
            }
        }
        if !(ssdo.radius.is_finite() && ssdo.radius > 0.0 && ssdo.radius <= 10.0) {
            return bad(format!(
                "SSDO radius {} must be in (0, 10] scene radii",
                ssdo.radius
            ));
        }
        if ssdo.filter != 0
            && (ssdo.filter.is_multiple_of(2) || ssdo.filter > SsdoConfig::MAX_FILTER)
        {
            return bad(format!(
                "bilateral filter side {} must be odd and at most {} (or off)",
                ssdo.filter,
                SsdoConfig::MAX_FILTER
            ));
        }
        if !(1..=2).contains(&ssdo.scale) {
            return bad(format!(
                "SSDO resolution divisor {} must be 1 (full) or 2 (half resolution)",
                ssdo.scale
            ));
        }
        if enabled && reuse {
            if ssdo.form == SsdoForm::TwoStep {
                return bad(
                    "SSDO's cache accumulates the one-step form (and --ssdo ssao): two steps \
                     need --reuse off"
                        .into(),
                );
            }
            if ssdo.scale != 1 {
                return bad(
                    "SSDO's cache runs at full resolution: --ssdo-scale 0.5 needs --reuse off"
                        .into(),
                );
            }
        }
        Ok(())
    }
}

/// `--ssdo-scale`: `1` or `0.5` (also `1/2`), returned as the resolution divisor.
pub fn parse_ssdo_scale(s: &str) -> Result<u32, String> {
    match s.trim() {
        "1" | "1.0" => Ok(1),
        "0.5" | ".5" | "1/2" => Ok(2),
        _ => Err(format!(
            "--ssdo-scale takes 1 (full resolution) or 0.5 (half), not {s:?}"
        )),
    }
}

/// `--bilateral`: an odd side up to 31, or `off` (0).
pub fn parse_bilateral(s: &str) -> Result<u32, String> {
    if s == "off" {
        return Ok(0);
    }
    match s.parse::<u32>() {
        Ok(n) if n % 2 == 1 && n <= SsdoConfig::MAX_FILTER => Ok(n),
        _ => Err(format!(
            "--bilateral takes an odd side from 1 to {} or off, not {s:?}",
            SsdoConfig::MAX_FILTER
        )),
    }
}
