//! The frame's one reprojection: every effect with a history is a lane of the shared
//! reprojection pass (registry order), so the G-buffer, the previous position and the
//! disocclusion test are read and computed once per pixel whatever the number of effects.

use crate::effects::resolve::EffectResources;
use crate::effects::{Effect, FrameInfo, Recording};
use crate::error::Result;
use crate::passes::decl::Resolve;
use crate::passes::reproject::{LaneFrame, ReprojectPass, MAX_LANES};
use crate::passes::PassId;
use crate::resources::targets::Targets;
use crate::resources::temporal_effect::TemporalEffect;
use crate::vk::{Context, DescriptorPool};
use ash::vk;
use std::sync::Arc;

/// The pass, absent when no effect keeps a history.
pub struct Reprojection {
    pass: Option<ReprojectPass>,
}

/// An effect's lane resources: its history, moments, state and counters.
fn lane<'a>(targets: &'a Targets, t: &'a TemporalEffect) -> EffectResources<'a> {
    EffectResources {
        targets,
        temporal: Some(t),
        own: &[],
        own_buffers: &[],
    }
}

/// The G-buffer every lane shares.
fn lane_shared_resources(targets: &Targets) -> EffectResources<'_> {
    EffectResources {
        targets,
        temporal: None,
        own: &[],
        own_buffers: &[],
    }
}

/// The effects with a history, with their index among all effects.
fn temporals(
    effects: &[Box<dyn Effect>],
) -> impl Iterator<Item = (usize, &dyn Effect, &TemporalEffect)> {
    effects
        .iter()
        .enumerate()
        .filter_map(|(i, e)| e.temporal().map(|t| (i, e.as_ref(), t)))
}

impl Reprojection {
    pub fn new(
        ctx: &Arc<Context>,
        pool: &DescriptorPool,
        effects: &[Box<dyn Effect>],
    ) -> Result<Self> {
        let formats: Vec<vk::Format> = temporals(effects)
            .map(|(_, _, t)| t.kind.history_format)
            .collect();
        let pass = match formats.len() {
            0 => None,
            _ => Some(ReprojectPass::new(ctx, pool, &formats)?),
        };
        Ok(Self { pass })
    }

    /// Point the pass at the current targets and histories (creation and resize).
    pub fn bind(
        &self,
        ctx: &Context,
        targets: &Targets,
        effects: &[Box<dyn Effect>],
    ) -> Result<()> {
        let Some(pass) = &self.pass else {
            return Ok(());
        };
        let lanes: Vec<EffectResources> = temporals(effects)
            .map(|(_, _, t)| lane(targets, t))
            .collect();
        let lanes: Vec<&dyn Resolve> = lanes.iter().map(|l| l as &dyn Resolve).collect();
        pass.bind(ctx, &lane_shared_resources(targets), &lanes)
    }

    /// Reset the counters of every effect that counts this frame, then one `reproject` region
    /// with one dispatch for every lane whose effect reuses its history this frame. Effects
    /// whose bit is set in `skipped` do not run this frame: their lanes and counters stay.
    pub fn record(
        &self,
        effects: &[Box<dyn Effect>],
        info: &FrameInfo<'_>,
        r: &mut Recording<'_>,
        skipped: u64,
    ) {
        let runs = |i: usize| skipped >> i & 1 == 0;
        for (_, e) in effects
            .iter()
            .enumerate()
            .filter(|(i, e)| runs(*i) && e.counts(info.config))
        {
            if let Some(temporal) = e.temporal() {
                temporal.reset_counters(&r.rec, r.tracker);
            }
        }
        let Some(pass) = &self.pass else {
            return;
        };
        // Fixed-size arrays: nothing is allocated per frame. Unused entries point at the
        // G-buffer resolver and are never passed on.
        let targets = info.targets;
        let shared = lane_shared_resources(targets);
        let mut resources: [Option<EffectResources>; MAX_LANES] = std::array::from_fn(|_| None);
        let mut frames = [LaneFrame::default(); MAX_LANES];
        let mut count = 0;
        for ((i, e, t), (res, frame)) in
            temporals(effects).zip(resources.iter_mut().zip(&mut frames))
        {
            let push = e.push();
            *res = Some(lane(targets, t));
            *frame = LaneFrame {
                active: runs(i) && e.reprojects(info),
                history_valid: push.history_valid != 0,
                block_shift: t.kind.block_shift,
                refresh_rect: push.refresh_rect,
                moved: if info.config.temporal.invalidate {
                    t.kind.moved.code(info.config)
                } else {
                    0
                },
                reach_radius: t.kind.moved.radius(info.config),
                // The shader starts only lanes whose history is valid.
                reaccumulate: info.starts_reaccumulating(&t.kind),
                stop_reaccumulating: info.changes_reach(&t.kind),
            };
            count += 1;
        }
        if !frames.iter().any(|l| l.active) {
            return;
        }
        let lanes: [(&dyn Resolve, LaneFrame); MAX_LANES] = std::array::from_fn(|k| {
            let res: &dyn Resolve = match &resources[k] {
                Some(r) => r,
                None => &shared,
            };
            (res, frames[k])
        });
        let lanes = &lanes[..count];
        let size = (targets.width, targets.height);
        r.timed(PassId::REPROJECT, |rec, tr| {
            pass.record(rec, tr, info.frame, &shared, lanes, size)
        });
    }
}
