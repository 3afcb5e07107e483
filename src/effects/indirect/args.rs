//! The indirect light's command-line options (flattened into every subcommand that renders,
//! through the registry's `EffectArgs`) and what they make of `IndirectConfig`.

use super::config::{IndirectConfig, IndirectFilter};
use crate::config::parse::{parse_on_off, parse_vpls};
use clap::Args;

#[derive(Args, Debug, Clone)]
pub struct IndirectArgs {
    /// VPLs gathered per pixel and frame for indirect light (`all`: every RSM texel).
    #[arg(long, default_value = "512", value_parser = parse_vpls)]
    pub vpls: u32,
    /// Screen-space visibility test of each VPL (Lin 2013 section 3.3.1; about halves speed).
    #[arg(long)]
    pub vpl_visibility: bool,
    /// Interleaved VPL gather: the pixels of each NxN block gather disjoint VPL subsets and a
    /// geometry-aware NxN filter combines them (1 = off, up to 8).
    #[arg(long, default_value_t = IndirectConfig::default().interleave, value_parser = clap::value_parser!(u32).range(1..=IndirectConfig::MAX_INTERLEAVE as i64))]
    pub interleave: u32,
    /// Lanes that share each low-resolution sample's VPLs in the half-resolution gather (a
    /// power of two, 1-64; more lanes hide a GPU's memory latency, fewer sum less).
    #[arg(long, default_value_t = IndirectConfig::default().vpl_lanes)]
    pub vpl_lanes: u32,
    /// How indirect light is smoothed over time: the thesis's cache, or one of the per-frame
    /// filters of a new noisy gather of --vpls per pixel each frame.
    #[arg(long, value_enum, default_value_t = IndirectFilter::Accumulate)]
    pub indirect_filter: IndirectFilter,
    /// The per-frame filters' noisy gather at half resolution: one pixel of each 2x2 block
    /// gathers (each in turn), the others take its sample where they lie on its surface.
    #[arg(long, default_value = "off", value_parser = parse_on_off, action = clap::ArgAction::Set)]
    pub noisy_half_res: bool,
    /// Gather indirect light at half resolution with geometry-aware upsampling.
    #[arg(long, default_value = "on", value_parser = parse_on_off, action = clap::ArgAction::Set)]
    pub half_res: bool,
}

impl IndirectArgs {
    /// The indirect light's configuration these options describe (validated with the rest by
    /// `RenderConfig::validate`).
    pub fn config(&self) -> IndirectConfig {
        IndirectConfig {
            vpls: self.vpls,
            visibility: self.vpl_visibility,
            half_res: self.half_res,
            interleave: self.interleave,
            vpl_lanes: self.vpl_lanes,
            filter: self.indirect_filter,
            noisy_half_res: self.noisy_half_res,
            ..IndirectConfig::default()
        }
    }
}
