//! SVGF's command-line options (flattened into every subcommand that renders, through the
//! registry's `EffectArgs`) and what they make of `SvgfConfig`.

use super::config::{parse_sigma, parse_weight, SvgfConfig, SvgfHistory};
use clap::Args;

#[derive(Args, Debug, Clone)]
pub struct SvgfArgs {
    /// SVGF (`--indirect-filter svgf`): a-trous wavelet iterations after the temporal
    /// accumulation (0-10; the article: 5).
    #[arg(long, default_value_t = SvgfConfig::default().iterations, value_parser = clap::value_parser!(u32).range(0..=SvgfConfig::MAX_ITERATIONS as i64))]
    pub svgf_iterations: u32,
    /// SVGF: smallest weight of a new sample in the colour's running mean, in (0, 1] (the
    /// article: 0.2).
    #[arg(long, default_value_t = SvgfConfig::default().alpha, value_parser = parse_weight)]
    pub svgf_alpha: f32,
    /// SVGF: the same for the luminance moments that give the variance.
    #[arg(long, default_value_t = SvgfConfig::default().alpha_moments, value_parser = parse_weight)]
    pub svgf_alpha_moments: f32,
    /// SVGF: the smallest weight of both once the light and the scene have held still for
    /// --svgf-alpha's settle time (the diffuse indirect light of a still light does not change
    /// when only the camera moves); at or above --svgf-alpha (the default) it changes nothing.
    #[arg(long, default_value_t = SvgfConfig::default().alpha_still, value_parser = parse_weight)]
    pub svgf_alpha_still: f32,
    /// SVGF: how last frame's colour and moments are read at the pixel's surface: `nearest`
    /// texel, or the article's `bilinear` tap tested per texel (blurs a long history).
    #[arg(long, value_enum, default_value_t = SvgfConfig::default().history)]
    pub svgf_history: SvgfHistory,
    /// SVGF luminance edge-stopping sigma_l, in standard deviations of the filtered variance
    /// (the article: 4).
    #[arg(long, default_value_t = SvgfConfig::default().sigma_luminance, value_parser = parse_sigma)]
    pub svgf_sigma_luminance: f32,
    /// SVGF normal edge-stopping exponent sigma_n of max(0, n . n_q) (the article: 128).
    #[arg(long, default_value_t = SvgfConfig::default().sigma_normal, value_parser = parse_sigma)]
    pub svgf_sigma_normal: f32,
    /// SVGF depth edge-stopping sigma_z, in multiples of the change the depth gradient
    /// predicts (the article: 1).
    #[arg(long, default_value_t = SvgfConfig::default().sigma_depth, value_parser = parse_sigma)]
    pub svgf_sigma_depth: f32,
}

impl SvgfArgs {
    /// The SVGF configuration these options describe (validated with the rest by
    /// `RenderConfig::validate`).
    pub fn config(&self) -> SvgfConfig {
        SvgfConfig {
            iterations: self.svgf_iterations,
            alpha: self.svgf_alpha,
            alpha_moments: self.svgf_alpha_moments,
            alpha_still: self.svgf_alpha_still,
            history: self.svgf_history,
            sigma_luminance: self.svgf_sigma_luminance,
            sigma_normal: self.svgf_sigma_normal,
            sigma_depth: self.svgf_sigma_depth,
        }
    }
}
