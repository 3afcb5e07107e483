//! The dependency table: for each pass, the scene changes that make it run again, derived from
//! the passes' declarations. A pass depends on the inputs it reads itself (`PassId::inputs`)
//! and, through its resource declaration (`PassLayout::binds`), on whatever the passes that
//! wrote the resources it reads depend on. The frame planner keys each effect on its passes'
//! changes (`skip.rs`), `explain` prints the table (`ssgi bench --explain-skips`,
//! docs/ARCHITECTURE.md), and tests/skip.rs compares the passes each change records with it.

use crate::config::RenderConfig;
use crate::effects::{Effect, EffectId, REGISTRY};
use crate::passes::decl::Slot;
use crate::passes::{Change, PassId, PassLayout};
use std::collections::HashMap;

/// Whether `e` accumulates into a reused history under `config`.
pub fn accumulates(config: &RenderConfig, e: &dyn Effect) -> bool {
    config.temporal.reuse && e.counts(config) && e.temporal().is_some()
}

/// A set of changes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Changes(u8);

impl Changes {
    pub fn of(list: &[Change]) -> Self {
        Self(list.iter().fold(0, |m, &c| m | 1 << c as u8))
    }

    pub fn contains(self, c: Change) -> bool {
        self.0 >> c as u8 & 1 == 1
    }

    pub fn list(self) -> Vec<Change> {
        Change::ALL
            .into_iter()
            .filter(|&c| self.contains(c))
            .collect()
    }
}

impl std::ops::BitOr for Changes {
    type Output = Changes;
    fn bitor(self, o: Changes) -> Changes {
        Changes(self.0 | o.0)
    }
}

impl std::ops::BitOrAssign for Changes {
    fn bitor_assign(&mut self, o: Changes) {
        self.0 |= o.0;
    }
}

/// Where what a slot holds comes from.
#[derive(Clone, Copy, PartialEq)]
enum Source {
    /// A resource one pass writes for all (last frame's G-buffer: the same pass's).
    Shared(Slot),
    /// The effect's own images and buffers: its passes and its reprojection lane.
    Local,
    /// An effect's composite term: any effect's output.
    Term,
}

fn source(slot: Slot) -> Source {
    match slot {
        Slot::GPositionPrev => Source::Shared(Slot::GPosition),
        Slot::GNormalPrev => Source::Shared(Slot::GNormal),
        Slot::History
        | Slot::HistoryPrev
        | Slot::Moments
        | Slot::MomentsPrev
        | Slot::Registration
        | Slot::RegistrationPrev
        | Slot::State
        | Slot::Counters
        | Slot::Own(_)
        | Slot::OwnBuffer(_) => Source::Local,
        Slot::Term(_) => Source::Term,
        s => Source::Shared(s),
    }
}

/// What one reprojection lane reads itself: the light only feeds the shadow lane's reach on
/// the shadow map, and the shadow effect's own passes read the light anyway.
const LANE: &[Change] = &[Change::Camera, Change::Object, Change::Config];

/// Every pass's changes and every effect's (the union of its passes').
pub struct Dependencies {
    passes: HashMap<PassId, Changes>,
    pub effects: Vec<Changes>,
}

impl Dependencies {
    pub fn pass(&self, p: PassId) -> Changes {
        at(&self.passes, p)
    }
}

/// A pass's changes in `t` (none until the fixed point reaches it).
fn at(t: &HashMap<PassId, Changes>, p: PassId) -> Changes {
    t.get(&p).copied().unwrap_or_default()
}

/// The changes each pass of `frame` (the passes every frame runs) and of each effect of
/// `effects` (their layouts) depends on: a fixed point, as histories feed themselves.
pub fn derive(frame: &[PassLayout], effects: &[Vec<PassLayout>]) -> Dependencies {
    let mut t: HashMap<PassId, Changes> = HashMap::new();
    let mut local = vec![Changes::default(); effects.len()];
    let all = || frame.iter().chain(effects.iter().flatten());
    loop {
        let before = (t.clone(), local.clone());
        let producer = |slot: Slot, t: &HashMap<PassId, Changes>| {
            all()
                .filter(|l| l.binds.iter().any(|b| b.slot == slot && b.usage.writes()))
                .fold(Changes::default(), |c, l| c | at(t, l.pass))
        };
        let any_effect = effects
            .iter()
            .flatten()
            .fold(Changes::default(), |c, l| c | at(&t, l.pass));
        // What a pass reads: its own inputs, and its sources' changes.
        let read = |l: &PassLayout, own: Changes, inputs: Changes, t: &HashMap<PassId, Changes>| {
            l.binds
                .iter()
                .filter(|b| b.usage.reads())
                .fold(inputs, |c, b| {
                    c | match source(b.slot) {
                        Source::Shared(s) => producer(s, t),
                        Source::Local => own,
                        Source::Term => any_effect,
                    }
                })
        };
        let mut lane_shared = Changes::of(LANE);
        for l in frame.iter().filter(|l| l.pass == PassId::REPROJECT) {
            lane_shared |= read(l, Changes::default(), Changes::of(LANE), &t);
        }
        let mut next = t.clone();
        for l in frame.iter().filter(|l| l.pass != PassId::REPROJECT) {
            *next.entry(l.pass).or_default() |=
                read(l, Changes::default(), Changes::of(l.pass.inputs()), &t);
        }
        let mut reproject = Changes::of(PassId::REPROJECT.inputs()) | lane_shared;
        for (e, layouts) in effects.iter().enumerate() {
            for l in layouts {
                *next.entry(l.pass).or_default() |=
                    read(l, local[e], Changes::of(l.pass.inputs()), &t);
            }
            let writers = layouts
                .iter()
                .filter(|l| {
                    l.binds
                        .iter()
                        .any(|b| b.usage.writes() && source(b.slot) == Source::Local)
                })
                .fold(Changes::default(), |c, l| c | at(&next, l.pass));
            local[e] |= lane_shared | writers;
            reproject |= local[e];
        }
        *next.entry(PassId::REPROJECT).or_default() |= reproject;
        t = next;
        if (&t, &local) == (&before.0, &before.1) {
            break;
        }
    }
    let effects = effects
        .iter()
        .map(|layouts| {
            layouts
                .iter()
                .fold(Changes::default(), |c, l| c | at(&t, l.pass))
        })
        .collect();
    Dependencies { passes: t, effects }
}

/// The layouts of `effects`, found by their registrations.
fn effect_layouts(effects: &[Box<dyn Effect>]) -> Vec<Vec<PassLayout>> {
    effects
        .iter()
        .map(|e| {
            REGISTRY
                .iter()
                .find(|r| r.id == e.id())
                .map(|r| (r.layouts)())
                .unwrap_or_default()
        })
        .collect()
}

/// The dependencies of the passes every frame runs and of `effects`.
pub fn of(effects: &[Box<dyn Effect>]) -> Dependencies {
    derive(&super::catalog::frame_layouts(), &effect_layouts(effects))
}

/// One row of the dependency table: a pass and the changes that make it run again.
pub struct Trigger {
    pub pass: PassId,
    pub changes: Vec<Change>,
    /// The effect the pass belongs to, and whether it accumulates (it then also runs on
    /// until its history converges).
    pub effect: Option<(EffectId, bool)>,
}

/// The dependency table of `effects` under `config`: a row for each pass this configuration
/// may record, with the changes that make it run again.
pub fn triggers(config: &RenderConfig, effects: &[Box<dyn Effect>]) -> Vec<Trigger> {
    let d = of(effects);
    let row = |pass: PassId, effect| Trigger {
        pass,
        changes: d.pass(pass).list(),
        effect,
    };
    let mut rows = vec![row(PassId::LIGHT_VIEW, None), row(PassId::GBUFFER, None)];
    if config.gbuffer.visibility() {
        rows.push(row(PassId::GBUFFER_RESOLVE, None));
    }
    for e in effects {
        for &pass in e.passes() {
            rows.push(row(pass, Some((e.id(), accumulates(config, e.as_ref())))));
        }
    }
    rows.push(row(PassId::REPROJECT, None));
    rows.push(row(PassId::COMPOSITE, None));
    for stage in crate::post::REGISTRY.iter().filter(|r| (r.enabled)(config)) {
        rows.extend(stage.passes.iter().map(|&p| row(p, None)));
    }
    let order = super::catalog::all_passes();
    rows.sort_by_key(|t| order.iter().position(|p| *p == t.pass));
    rows.dedup_by_key(|t| t.pass);
    rows
}

/// Why a row of the dependency table runs again, in words.
fn why(t: &Trigger) -> String {
    let names: Vec<&str> = t.changes.iter().map(|c| c.name()).collect();
    let mut out = names.join(", ");
    match (t.pass, t.effect) {
        (PassId::LIGHT_VIEW, _) => {
            out += " (objects whose bounds, this frame or the last, meet the light's frustum)"
        }
        (PassId::REPROJECT, _) => out += "; a lane per effect with a reused history that runs",
        (_, Some((id, true))) => {
            out += &format!("; {id:?}: every frame until its history converges")
        }
        (_, Some((id, false))) => out += &format!("; {id:?} effect"),
        _ => {}
    }
    out
}

/// The dependency table of `effects` under `config`: for each pass, what makes it run again.
pub fn explain(config: &RenderConfig, effects: &[Box<dyn Effect>]) -> String {
    let mut out = String::from(
        "pass (those this configuration may record)  runs again when this changed in the last \
         two frames (from each pass's inputs and the passes whose outputs it reads)\n",
    );
    for t in triggers(config, effects) {
        out += &format!("{:<18} {}\n", t.pass.name(), why(&t));
    }
    if !config.skip_unchanged {
        out += "(--skip-unchanged off: every pass runs every frame)\n";
    }
    out
}
