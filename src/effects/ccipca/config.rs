//! CCIPCA's configuration (Chen, Lei & Chang 2012): its bases, step weighting, projection
//! order, basis filter, orthogonalization, adaptive sampling and memory, and their
//! validation. Plain data: the bottom layer's `RenderConfig` holds it, so it uses nothing above
//! `error`. (Which filter the indirect light takes, `--indirect-filter`, is the indirect
//! light's choice: `IndirectConfig::filter`.)

use crate::error::{Error, Result};
use serde::Serialize;

/// Incremental principal components of the noisy indirect light, per pixel (src/reference/
/// ccipca.rs is its CPU model).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct CcipcaConfig {
    /// Basis images (Chen et al.'s Table 1: 3, 5, 7).
    pub bases: u32,
    /// Whose sample count sets each pixel's step (Chen et al.'s per-pixel weighting,
    /// on the first basis or on all, or uniform).
    pub weighting: CcipcaWeighting,
    /// Project each frame on the bases after updating them from it (the article) or
    /// on last frame's.
    pub project: CcipcaProject,
    /// Radius [px] of the joint bilateral filter applied to every basis after the
    /// updates (the article's basis filtering); 0 = off.
    pub basis_filter: u32,
    /// Orthogonalize after warps only, or after basis filtering too.
    pub orthogonalize: CcipcaOrthogonalize,
    /// Adaptive sampling: VPLs gathered by a pixel new to the view after a camera
    /// move (0 = `vpls`, as any other pixel).
    pub new_pixel_vpls: u32,
    /// Samples after which a pixel's step stops shrinking (see
    /// src/effects/ccipca/model.rs): the filter's memory, in frames.
    pub max_age: u32,
    /// How far a frame goes: everything, or (tests) only the warp and
    /// orthogonalization. Not on the command line and not in reports.
    #[serde(skip)]
    pub stages: CcipcaStages,
}

impl CcipcaConfig {
    /// Most bases (the shaders' partial sums are sized for them).
    pub const MAX_BASES: u32 = 8;
    /// Largest basis filter radius: its window is read once per basis and pixel.
    pub const MAX_BASIS_FILTER: u32 = 8;

    /// Its rules: counts and radii within what the shaders are sized for, a clear error for
    /// each, never a clamp.
    pub fn validate(&self) -> Result<()> {
        let bad = |m: String| Err(Error::Config(m));
        if !(1..=CcipcaConfig::MAX_BASES).contains(&self.bases) {
            return bad(format!(
                "{} CCIPCA bases outside 1..={}",
                self.bases,
                CcipcaConfig::MAX_BASES
            ));
        }
        if self.new_pixel_vpls > 16384 {
            return bad(format!(
                "{} VPLs for a new pixel is more than 16384",
                self.new_pixel_vpls
            ));
        }
        if self.basis_filter > CcipcaConfig::MAX_BASIS_FILTER {
            return bad(format!(
                "CCIPCA basis filter radius {} px is more than {}",
                self.basis_filter,
                CcipcaConfig::MAX_BASIS_FILTER
            ));
        }
        if !(1..=1 << 20).contains(&self.max_age) {
            return bad(format!(
                "CCIPCA memory {} frames outside 1..=1048576",
                self.max_age
            ));
        }
        Ok(())
    }
}

impl Default for CcipcaConfig {
    fn default() -> Self {
        Self {
            bases: 3,
            weighting: CcipcaWeighting::PerPixel,
            project: CcipcaProject::Before,
            basis_filter: 2,
            orthogonalize: CcipcaOrthogonalize::Warp,
            new_pixel_vpls: 0,
            max_age: 256,
            stages: CcipcaStages::All,
        }
    }
}

/// Whose sample count sets a CCIPCA update's step at a pixel.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum CcipcaWeighting {
    /// The pixel's own for every basis (Chen et al. section 3.4.2): a pixel new to the view
    /// takes large steps.
    #[default]
    PerPixel,
    /// The pixel's own for the first basis, the frames since the restart for the others.
    FirstBasis,
    /// The frames since the bases restarted, the same for every pixel (plain CCIPCA).
    Uniform,
}

/// Which bases CCIPCA projects a frame on.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum CcipcaProject {
    /// Last frame's (warped) bases, before the frame updates them: the frame's own noise is
    /// not in the bases it is projected on. A pixel new to the view is dark for one frame.
    #[default]
    Before,
    /// The bases updated from the frame (Chen et al.'s Figure 2: warp, update, project).
    After,
}

/// When CCIPCA orthogonalizes its bases (the article's Algorithm 2).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum CcipcaOrthogonalize {
    /// After a warp only (the article): on a still camera basis filtering tilts the bases
    /// towards each other until they are nearly one (|cos| 0.99 after 25 frames), so the
    /// projection acts as on the first basis alone.
    #[default]
    Warp,
    /// Also after every basis filtering: the bases stay orthogonal, `--bases` of them.
    Always,
}

/// The CCIPCA passes a frame records.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CcipcaStages {
    #[default]
    All,
    /// Only the warp and the orthogonalization: the bases as the updates would find them.
    WarpOnly,
}
