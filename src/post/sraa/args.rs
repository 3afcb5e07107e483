//! SRAA's command-line options (flattened into every subcommand that renders, through the post
//! registry's `PostArgs`) and what they make of `SraaConfig`.

use super::config::SraaConfig;
use clap::Args;

#[derive(Args, Debug, Clone)]
pub struct SraaArgs {
    /// SRAA's depth scale (eq 1's sigma_z) on the relative difference of eye distances.
    #[arg(long, default_value_t = SraaConfig::default().sigma_z)]
    pub sraa_sigma_z: f32,
    /// SRAA's normal scale (eq 1's sigma_n) on 1 - sat(n_j . n_i).
    #[arg(long, default_value_t = SraaConfig::default().sigma_n)]
    pub sraa_sigma_n: f32,
    /// `sraa-shadow`'s scale on the difference of two samples' shadow tests (0 or 1).
    #[arg(long, default_value_t = SraaConfig::default().sigma_shadow)]
    pub sraa_sigma_shadow: f32,
}

impl SraaArgs {
    /// The weights these options describe (validated by `RenderConfig::validate`).
    pub fn config(&self) -> SraaConfig {
        SraaConfig {
            sigma_z: self.sraa_sigma_z,
            sigma_n: self.sraa_sigma_n,
            sigma_shadow: self.sraa_sigma_shadow,
        }
    }
}
