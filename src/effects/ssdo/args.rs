//! SSDO's command-line options (flattened into every subcommand that renders, through the
//! registry's `EffectArgs`) and what they make of `SsdoConfig`.

use super::config::{parse_bilateral, parse_ssdo_scale, AdaptiveSamples, SsdoConfig, SsdoForm};
use clap::Args;

#[derive(Args, Debug, Clone)]
pub struct SsdoArgs {
    /// SSDO's form (with `--effects ...,ssdo`): one-step (modulation factor and bounce in one
    /// pass, Szentandrasi section 4.1), two-step (directional occlusion, then the bounce), or
    /// ssao (section 3.1's SSAO on SSDO's samples, filter and resolution; ambient only).
    #[arg(long, value_enum, default_value = "one-step")]
    pub ssdo: SsdoForm,
    /// SSDO hemisphere samples per pixel (whole Halton periods of 10 spread evenly), or
    /// `adaptive[:MIN-MAX]`: per block from a pre-pass over normals and depths (default 20-50,
    /// the paper's).
    #[arg(long, default_value = "20", value_parser = parse_ssdo_samples)]
    pub ssdo_samples: SsdoSamples,
    /// Resolution divisor of the adaptive sample count's pre-pass.
    #[arg(long, default_value_t = AdaptiveSamples::PAPER.scale, value_parser = clap::value_parser!(u32).range(1..=SsdoConfig::MAX_PREPASS_SCALE as i64))]
    pub ssdo_prepass_scale: u32,
    /// The adaptive count's thresholds, ascending, one per period above the minimum (default
    /// 0.02,0.1,0.3[,0.6]): a block's change measure (1 - cos of its creases, or its steps in
    /// units of its size) above each adds 10 samples.
    #[arg(long, value_delimiter = ',')]
    pub ssdo_thresholds: Option<Vec<f32>>,
    /// SSDO hemisphere radius, as a fraction of the scene's bounding radius.
    #[arg(long, default_value_t = SsdoConfig::default().radius)]
    pub ssdo_radius: f32,
    /// Side of SSDO's separable geometry-aware bilateral filter (odd, up to 31), or `off`.
    #[arg(long, default_value = "11", value_parser = parse_bilateral)]
    pub bilateral: u32,
    /// Resolution of SSDO and its filter: 1 (full) or 0.5 (half, then joint bilateral
    /// upsampling with a 3x3 geometry-aware kernel).
    #[arg(long, default_value = "1", value_parser = parse_ssdo_scale)]
    pub ssdo_scale: u32,
}

impl SsdoArgs {
    /// The SSDO configuration these options describe (validated with the rest by
    /// `RenderConfig::validate`).
    pub fn config(&self) -> SsdoConfig {
        SsdoConfig {
            form: self.ssdo,
            samples: match self.ssdo_samples {
                SsdoSamples::Fixed(n) => n,
                SsdoSamples::Adaptive { max, .. } => max,
            },
            adaptive: match self.ssdo_samples {
                SsdoSamples::Fixed(_) => None,
                SsdoSamples::Adaptive { min, max } => {
                    let mut a = AdaptiveSamples::range(min, max, self.ssdo_prepass_scale);
                    if let Some(t) = &self.ssdo_thresholds {
                        a.threshold_count = t.len().min(5) as u32;
                        a.thresholds = [0.0; 4];
                        for (slot, v) in a.thresholds.iter_mut().zip(t) {
                            *slot = *v;
                        }
                    }
                    Some(a)
                }
            },
            radius: self.ssdo_radius,
            filter: self.bilateral,
            scale: self.ssdo_scale,
        }
    }
}

/// `--ssdo-samples`: a fixed count, or per block from the pre-pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SsdoSamples {
    Fixed(u32),
    Adaptive { min: u32, max: u32 },
}

/// `N`, `adaptive` (20-50) or `adaptive:MIN-MAX` (multiples of the Halton period 10, one to
/// four periods apart).
pub fn parse_ssdo_samples(s: &str) -> Result<SsdoSamples, String> {
    let max = SsdoConfig::MAX_SAMPLES;
    if let Ok(n) = s.parse::<u32>() {
        return if (1..=max).contains(&n) {
            Ok(SsdoSamples::Fixed(n))
        } else {
            Err(format!("--ssdo-samples {n} outside 1..={max}"))
        };
    }
    let range = match s.strip_prefix("adaptive") {
        Some("") => Some((20, 50)),
        Some(r) => r.strip_prefix(':').and_then(|r| -> Option<(u32, u32)> {
            let (a, b) = r.split_once('-')?;
            Some((a.trim().parse().ok()?, b.trim().parse().ok()?))
        }),
        None => None,
    };
    let period = SsdoConfig::HALTON_PERIOD;
    match range {
        Some((min, max_n))
            if min > 0
                && min.is_multiple_of(period)
                && max_n.is_multiple_of(period)
                && max_n > min
                && max_n - min <= 4 * period
                && max_n <= max =>
        {
            Ok(SsdoSamples::Adaptive { min, max: max_n })
        }
        _ => Err(format!(
            "--ssdo-samples takes a count, `adaptive` or `adaptive:MIN-MAX` (multiples of {period}, \
             one to four periods apart), not {s:?}"
        )),
    }
}
