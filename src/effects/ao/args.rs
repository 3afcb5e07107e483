//! SSAO's command-line options (flattened into every subcommand that renders, through the
//! registry's `EffectArgs`) and what they make of `AoConfig`.

use super::config::{AoConfig, AoEstimator};
use crate::config::parse::{parse_attenuation, parse_on_off};
use clap::Args;

#[derive(Args, Debug, Clone)]
pub struct AoArgs {
    /// SSAO estimator.
    #[arg(long = "ao", value_enum, default_value = "thesis")]
    pub ao_estimator: AoEstimator,
    /// SSAO samples per pattern (thesis: 8 directions x 4 steps for 32).
    #[arg(long, default_value_t = 32)]
    pub ao_samples: u32,
    /// Far SSAO taps read point-sampled levels of the G-buffer position, up to this level
    /// (0 = off: every tap reads the full-resolution G-buffer, the estimator as published).
    #[arg(long, default_value_t = AoConfig::default().position_mips, value_parser = clap::value_parser!(u32).range(0..=AoConfig::MAX_POSITION_MIPS as i64))]
    pub ao_position_mips: u32,
    /// GTAO horizon-search steps on each side of a slice (`--ao gtao`; --ao-samples / (2
    /// steps) slices per pattern, at least one).
    #[arg(long, default_value_t = AoConfig::default().steps)]
    pub ao_steps: u32,
    /// Eq 7's attenuation D(d) = 1 + A d + B d^2 as `A:B` (d in units of the AO radius);
    /// `0:0` is binary visibility within the radius. The ground truth's AO follows it.
    #[arg(long, default_value = "0:1", value_parser = parse_attenuation, value_name = "A:B", allow_hyphen_values = true)]
    pub ao_attenuation: [f32; 2],
    /// GTAO with the cache: denoise each fresh pattern (5x5, edge-aware) before it enters the
    /// history while the camera moves (`off`: raw patterns, as on a still view).
    #[arg(long, default_value = "on", value_parser = parse_on_off, action = clap::ArgAction::Set)]
    pub gtao_moving_denoise: bool,
}

impl AoArgs {
    /// The SSAO configuration these options describe (validated with the rest by
    /// `RenderConfig::validate`).
    pub fn config(&self) -> AoConfig {
        AoConfig {
            estimator: self.ao_estimator,
            samples: self.ao_samples,
            position_mips: self.ao_position_mips,
            steps: self.ao_steps,
            attenuation: self.ao_attenuation,
            moving_denoise: self.gtao_moving_denoise,
            ..AoConfig::default()
        }
    }
}
