//! CCIPCA's command-line options (flattened into every subcommand that renders, through the
//! registry's `EffectArgs`) and what they make of `CcipcaConfig`.

use super::config::{CcipcaConfig, CcipcaOrthogonalize, CcipcaProject, CcipcaWeighting};
use clap::Args;

#[derive(Args, Debug, Clone)]
pub struct CcipcaArgs {
    /// CCIPCA basis images (1..=8; Chen et al. use 3, 5 and 7).
    #[arg(long, default_value_t = CcipcaConfig::default().bases, value_parser = clap::value_parser!(u32).range(1..=CcipcaConfig::MAX_BASES as i64))]
    pub bases: u32,
    /// CCIPCA step per pixel: `per-pixel` from the pixel's own sample count in every basis
    /// (Chen et al.), `first-basis` from it in the first basis and from the frames since the
    /// restart in the others, `uniform` from the frames since the restart.
    #[arg(long, value_enum, default_value_t = CcipcaWeighting::PerPixel)]
    pub ccipca_weighting: CcipcaWeighting,
    /// CCIPCA: project each frame on last frame's bases, `before` updating them from it (they
    /// hold none of this frame's noise), or `after` (the article's order).
    #[arg(long, value_enum, default_value_t = CcipcaProject::Before)]
    pub ccipca_project: CcipcaProject,
    /// CCIPCA basis filtering: radius in pixels (0-8) of the joint bilateral filter that
    /// smooths every basis after the updates (0 = off).
    #[arg(long, default_value_t = CcipcaConfig::default().basis_filter, value_parser = clap::value_parser!(u32).range(0..=CcipcaConfig::MAX_BASIS_FILTER as i64))]
    pub ccipca_basis_filter: u32,
    /// CCIPCA: orthogonalize the bases after a warp only (the article), or `always`, after
    /// every basis filtering too (the bases stay orthogonal on a still camera).
    #[arg(long, value_enum, default_value_t = CcipcaOrthogonalize::Warp)]
    pub ccipca_orthogonalize: CcipcaOrthogonalize,
    /// CCIPCA adaptive sampling: VPLs gathered by a pixel new to the view after a camera move
    /// (0 = as many as any other pixel, --vpls; at most 16384).
    #[arg(long, default_value_t = 0, value_parser = clap::value_parser!(u32).range(0..=16384))]
    pub ccipca_new_pixel_vpls: u32,
    /// CCIPCA memory: frames after which a pixel's update step stops shrinking (1..=1048576).
    #[arg(long, default_value_t = CcipcaConfig::default().max_age, value_parser = clap::value_parser!(u32).range(1..=1 << 20))]
    pub ccipca_max_age: u32,
}

impl CcipcaArgs {
    /// The CCIPCA configuration these options describe (validated with the rest by
    /// `RenderConfig::validate`).
    pub fn config(&self) -> CcipcaConfig {
        CcipcaConfig {
            bases: self.bases,
            weighting: self.ccipca_weighting,
            project: self.ccipca_project,
            basis_filter: self.ccipca_basis_filter,
            orthogonalize: self.ccipca_orthogonalize,
            new_pixel_vpls: self.ccipca_new_pixel_vpls,
            max_age: self.ccipca_max_age,
            ..CcipcaConfig::default()
        }
    }
}
