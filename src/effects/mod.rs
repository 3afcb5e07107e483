//! Effects: direct light with PCF shadows, SSAO, one-bounce indirect light (accumulated, or
//! filtered by CCIPCA, a joint bilateral filter or SVGF), SSDO. Each is a folder here (its shaders in
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
pub mod svgf;

pub use effect::{
    every_pixel, refresh_dispatch, Effect, EffectId, FrameInfo, Recording, Registration, Setup,
    TermKind, Toggle,
};

use crate::config::sweep_key::SweepKey;
use crate::config::RenderConfig;
use crate::error::Result;
use crate::passes::{PassId, PassLayout};
use crate::reference::compose::Terms;
use crate::resources::targets::Target;

/// The registry, in recording order (also the composite's term order). Adding an effect is its
/// module and one line here.
pub const REGISTRY: &[Registration] = &[
    direct::REGISTRATION,
    ao::REGISTRATION,
    indirect::REGISTRATION,
    ccipca::REGISTRATION,
    jbf::REGISTRATION,
    svgf::REGISTRATION,
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

/// Every target a run may read back: the frame's own and each effect's views, in registry
/// order (`--target`, `--dump-targets`, the audit).
pub fn all_targets() -> Vec<Target> {
    let views = REGISTRY.iter().flat_map(|r| r.views).map(Target::Effect);
    Target::FRAME.into_iter().chain(views).collect()
}

/// The ground truth's buffers `config`'s final image estimates: those of every effect it
/// turns on.
pub fn estimated_terms(config: &RenderConfig) -> Terms {
    REGISTRY
        .iter()
        .filter(|r| (r.enabled)(config))
        .fold(Terms::NONE, |t, r| t.union((r.estimates)(config)))
}

/// The effects' own on/off settings, in registry order (the viewer's keys).
pub fn toggles() -> impl Iterator<Item = &'static Toggle> {
    REGISTRY.iter().flat_map(|r| r.toggles)
}

/// The `--effects` switches whose effects darken the ambient light (`Registration::ambient`):
/// a run has at most one of them on.
pub fn ambient_switches() -> Vec<&'static str> {
    let mut v: Vec<&'static str> = Vec::new();
    for r in REGISTRY.iter().filter(|r| r.ambient) {
        if !v.contains(&r.switch) {
            v.push(r.switch);
        }
    }
    v
}

/// Every effect's sweep keys, in registry order.
pub fn sweep_keys() -> impl Iterator<Item = &'static SweepKey> {
    REGISTRY.iter().flat_map(|r| r.sweep_keys)
}

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

/// Every pipeline of every effect, for the reflection check (also done when each pipeline is
/// built; `renderer::all_layouts` adds the frame's own and the post stages').
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
    pub svgf: svgf::args::SvgfArgs,
    #[command(flatten)]
    pub ssdo: ssdo::args::SsdoArgs,
}

impl EffectArgs {
    /// Write each effect's part of `config` from its options.
    pub fn apply(&self, config: &mut RenderConfig) {
        config.ao = self.ao.config();
        config.indirect = self.indirect.config();
        config.ccipca = self.ccipca.config();
        config.svgf = self.svgf.config();
        config.ssdo = self.ssdo.config();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::{Effects, IndirectFilter};

    #[test]
    fn each_effect_is_off_without_its_switch() {
        for r in REGISTRY {
            assert!(Effects::NAMES.contains(&r.switch), "{}", r.id.name());
            let mut config = RenderConfig {
                effects: Effects::parse(&Effects::NAMES.join(",")).unwrap(),
                ..Default::default()
            };
            config.effects.set(r.switch, false).unwrap();
            assert!(
                !(r.enabled)(&config),
                "{} runs without --effects {}",
                r.id.name(),
                r.switch
            );
        }
    }

    fn terms(effects: &str, change: impl Fn(&mut RenderConfig)) -> Terms {
        let mut config = RenderConfig {
            effects: Effects::parse(effects).unwrap(),
            ..Default::default()
        };
        change(&mut config);
        estimated_terms(&config)
    }

    #[test]
    fn the_estimated_terms_are_those_of_the_effects_that_run() {
        assert_eq!(terms("all", |_| {}), Terms::ALL);
        assert_eq!(terms("ao", |_| {}), Terms::AMBIENT_OCCLUSION);
        assert_eq!(terms("direct,normals", |_| {}), Terms::DIRECT);
        for filter in [
            IndirectFilter::Ccipca,
            IndirectFilter::Jbf11,
            IndirectFilter::Svgf,
        ] {
            let t = terms("indirect", |c| c.indirect.filter = filter);
            assert_eq!(t, Terms::INDIRECT, "{filter:?}");
        }
        // SSDO darkens the ambient light as AO does; its forms with a bounce add the indirect
        // light's near field.
        let ssao = terms("direct,ssdo", |c| {
            c.ssdo.form = ssdo::config::SsdoForm::Ssao
        });
        assert_eq!(ssao, terms("direct,ao", |_| {}));
        for form in [
            ssdo::config::SsdoForm::OneStep,
            ssdo::config::SsdoForm::TwoStep,
        ] {
            assert_eq!(terms("direct,ssdo", |c| c.ssdo.form = form), Terms::ALL);
        }
    }

    #[test]
    fn views_and_toggles_have_unique_names() {
        let unique = |mut names: Vec<&str>| {
            let n = names.len();
            names.sort_unstable();
            names.dedup();
            assert_eq!(names.len(), n, "a name repeats: {names:?}");
        };
        unique(all_targets().iter().map(|t| t.name()).collect());
        unique(toggles().map(|t| t.name).chain(Effects::NAMES).collect());
    }
}
