//! The indirect light's configuration (Lin 2013 section 3.3: the RSM gather, its VPL count,
//! visibility, half resolution, interleaving and lanes; and which filter makes it smooth over
//! time), and its own validation. Plain data: the bottom layer's `RenderConfig` holds it, so it
//! uses nothing above `error`.

use crate::error::{Error, Result};
use serde::Serialize;

/// One-bounce indirect light (Lin 2013 section 3.3).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct IndirectConfig {
    /// VPLs gathered per pixel and pattern; 0 = every RSM texel (the full gather).
    pub vpls: u32,
    /// The screen-space visibility test of each VPL (about halves the speed, the thesis says).
    pub visibility: bool,
    /// Gather at half resolution, upsample geometry-aware, fix up discarded pixels.
    pub half_res: bool,
    /// Interleaved sampling (Keller & Heidrich 2001): the pixels of each N x N block gather
    /// disjoint subsets of the VPLs (vpls / N^2 each) and a geometry-aware N x N filter puts
    /// them back together. 1 = every pixel gathers every VPL.
    pub interleave: u32,
    /// Lanes that share one low-resolution sample's VPLs in the compacted half-resolution
    /// gather (a power of two, 1-64): a GPU hides the RSM reads' latency only with enough lanes
    /// in flight, and one lane looping over every VPL is one long dependency chain.
    pub vpl_lanes: u32,
    /// What smooths indirect light over time: the thesis's accumulation, or a per-frame filter.
    pub filter: IndirectFilter,
    /// The per-frame filters' noisy gather at half resolution: one
    /// pixel of each 2x2 block gathers (each in turn), the others take its sample where they
    /// lie on its surface.
    pub noisy_half_res: bool,
    /// What the passes compute per pixel: the gather, or a test ramp. Not on the command line
    /// and not in reports.
    #[serde(skip)]
    pub input: IndirectInput,
}

/// How indirect light is made smooth over time.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum IndirectFilter {
    /// The thesis: reverse-reprojected accumulation (eqs 4-5) with half resolution,
    /// refresh and the rest of the cache.
    #[default]
    Accumulate,
    /// Chen, Lei & Chang 2012: a new noisy gather every frame (--vpls per pixel) projected on
    /// incrementally estimated principal components (CCIPCA).
    Ccipca,
    /// The same noisy gather, filtered within the frame by an 11x11 joint bilateral filter
    /// (the article's baseline).
    Jbf11,
    /// The same with a 17x17 window.
    Jbf17,
    /// Schied et al. 2017: the same noisy gather accumulated over time with its luminance
    /// moments, then an edge-avoiding a-trous wavelet guided by their variance (SVGF).
    Svgf,
}

/// The value the indirect passes compute for a pixel before upsampling and accumulation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum IndirectInput {
    /// Eq 9 from the reflective shadow map.
    #[default]
    Gather,
    /// Test input: the world position of the G-buffer texel each gather reads, as rgb. A
    /// linear function with a known value at every pixel, so the half-resolution sample
    /// positions and upsampling weights can be checked for an exact reconstruction.
    Ramp,
}

impl IndirectConfig {
    /// Largest interleaving block side: the reconstruction window must fit in the 9x9
    /// low-resolution tile of a block.
    pub const MAX_INTERLEAVE: u32 = 8;

    /// Nearest step of each VPL's screen-space visibility march [px]: eq 8's log spacing
    /// starting one and a half pixels out, like SSAO's default, so the march leaves the
    /// receiver's own pixel before testing depth.
    pub const MARCH_NEAR_PX: f32 = 1.5;

    /// Its own rules (per-invocation loop lengths, the interleaving and lane counts), a clear
    /// error for each, never a clamp. Rules that involve the shadow map or the cache are
    /// `RenderConfig::validate`'s.
    pub fn validate(&self) -> Result<()> {
        let bad = |m: String| Err(Error::Config(m));
        // Per-invocation loop lengths: llvmpipe stops loops after ~2^16 iterations per
        // invocation (the result is then silently wrong) and GPU drivers reset the device on
        // very long dispatches, so gathers are bounded.
        if self.vpls > 16384 {
            return bad(format!(
                "{} VPLs per pixel is more than 16384 (accumulate frames instead)",
                self.vpls
            ));
        }
        let il = self.interleave;
        if !(1..=IndirectConfig::MAX_INTERLEAVE).contains(&il) {
            return bad(format!(
                "interleaving block side {il} outside 1..={}",
                IndirectConfig::MAX_INTERLEAVE
            ));
        }
        let lanes = self.vpl_lanes;
        if !(lanes.is_power_of_two() && lanes <= 64) {
            return bad(format!(
                "--vpl-lanes {lanes}: lanes sharing a sample's VPLs must be a power of two from 1 \
                 to 64 (a workgroup's width)"
            ));
        }
        if self.vpls != 0 && self.vpls < il * il {
            return bad(format!(
                "{} VPLs cannot be split among the {} pixels of a {il}x{il} interleaving block \
                 (use at least {} VPLs or a smaller --interleave)",
                self.vpls,
                il * il,
                il * il
            ));
        }
        Ok(())
    }
}

impl Default for IndirectConfig {
    fn default() -> Self {
        Self {
            vpls: 512,
            visibility: false,
            half_res: true,
            interleave: 1,
            vpl_lanes: 16,
            filter: IndirectFilter::Accumulate,
            noisy_half_res: false,
            input: IndirectInput::Gather,
        }
    }
}
