//! Effects: direct light with PCF shadows, SSAO, one-bounce indirect light (accumulated, or
//! filtered by CCIPCA or a joint bilateral filter), SSDO. Each is a folder here (its shaders in
//! `shaders/<effect>/`) that owns its passes, its size-dependent images, its temporal history
//! and counters, its debug views and its contribution to the composite, and is registered in
//! [`create`] with one line. The renderer only walks the list (see docs/ARCHITECTURE.md).

pub mod ao;
pub mod ccipca;
pub mod direct;
pub mod effect;
pub mod indirect;
pub mod jbf;
pub mod normals;
pub mod resolve;
pub mod ssdo;

pub use effect::{
    every_pixel, refresh_dispatch, Effect, EffectId, FrameInfo, Recording, Registration, Setup,
    TermKind,
};

use crate::config::sweep_key::SweepKey;
use crate::config::RenderConfig;
use crate::error::Result;
use crate::passes::{PassId, PassLayout};

/// The registry, in recording order (also the composite's term order). Adding an effect is its
/// module and one line here.
pub const REGISTRY: &[Registration] = &[
    direct::REGISTRATION,
    ao::REGISTRATION,
    indirect::REGISTRATION,
    ccipca::REGISTRATION,
    jbf::REGISTRATION,
    ssdo::REGISTRATION,
    normals::REGISTRATION,
];

/// Every effect the configuration turns on, in registry order.
pub fn create(s: &mut Setup<'_>) -> Result<Vec<Box<dyn Effect>>> {
    REGISTRY
        .iter()
        .filter(|r| (r.enabled)(s.config))
        .map(|r| (r.create)(s))
        .collect()
}

/// Every effect's passes in registry order (a pass two effects share, CCIPCA's and the joint
/// bilateral filters' noisy gather, once).
pub fn effect_passes() -> Vec<PassId> {
    let mut v: Vec<PassId> = Vec::new();
    for p in REGISTRY.iter().flat_map(|r| r.passes) {
        if !v.contains(p) {
            v.push(*p);
        }
    }
    v
}

/// Every effect's sweep keys, in registry order.
pub fn sweep_keys() -> impl Iterator<Item = &'static SweepKey> {
    REGISTRY.iter().flat_map(|r| r.sweep_keys)
}

/// Every pipeline of every effect, for the reflection check (also done when each pipeline is
/// built; `renderer::all_layouts` adds the frame's own and the post stages').
/// Whether `config` runs an effect whose term darkens the ambient light (`Registration::ambient`).
pub fn ambient_enabled(config: &RenderConfig) -> bool {
    REGISTRY.iter().any(|r| r.ambient && (r.enabled)(config))
}

/// The timing groups of the effects whose term darkens the ambient light (a run has at most
/// one of them: they are exclusive).
pub fn ambient_groups() -> Vec<&'static str> {
    REGISTRY
        .iter()
        .filter(|r| r.ambient)
        .flat_map(|r| r.timing_groups.iter().map(|(g, _)| *g))
        .collect()
}

pub fn effect_layouts() -> Vec<PassLayout> {
    REGISTRY.iter().flat_map(|r| (r.layouts)()).collect()
}

/// Every effect's own command-line options, flattened into each subcommand that renders (an
/// effect adds its `Args` struct here and its part of the configuration in `apply`).
#[derive(clap::Args, Debug, Clone)]
pub struct EffectArgs {
    #[command(flatten)]
    pub ao: ao::args::AoArgs,
    #[command(flatten)]
    pub indirect: indirect::args::IndirectArgs,
    #[command(flatten)]
    pub ccipca: ccipca::args::CcipcaArgs,
    #[command(flatten)]
    pub ssdo: ssdo::args::SsdoArgs,
}

impl EffectArgs {
    /// Write each effect's part of `config` from its options.
    pub fn apply(&self, config: &mut RenderConfig) {
        config.ao = self.ao.config();
        config.indirect = self.indirect.config();
        config.ccipca = self.ccipca.config();
        config.ssdo = self.ssdo.config();
    }
}
