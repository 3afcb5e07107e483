//! Reverse reprojection (Lin 2013 eqs 1-3) of every temporal effect in one dispatch: the
//! G-buffer, the previous position and the disocclusion test once per pixel, then each effect's
//! history resampling, per-pixel state, disocclusion count and list of blocks needing work.
//! Each temporal effect is a lane: its resources sit at their own bindings, resolved by the
//! effect, and its push constants in its own members.

use super::compute::{parity_sets, FrameSet};
use super::decl::{self, Bind, Resolve, Slot, Use};
use super::layout::PassLayout;
use super::pass_id::PassId;
use crate::error::{Error, Result};
use crate::shaders::{self, ReprojectPush, ShaderModuleInfo};
use crate::vk::recorder::Recorder;
use crate::vk::{Context, DescriptorPool, Pipeline, SetWriter, Tracker};
use ash::vk;
use std::sync::Arc;

/// Temporal effects one reprojection serves (the shader's permutations).
pub const MAX_LANES: usize = 3;

/// What every lane shares: this frame's G-buffer (with its motion) and last frame's.
const SHARED: &[Bind] = &[
    Bind::new(0, Slot::GPosition, Use::Sampled),
    Bind::new(1, Slot::GNormal, Use::Sampled),
    Bind::new(2, Slot::GPositionPrev, Use::Sampled),
    Bind::new(3, Slot::GNormalPrev, Use::Sampled),
    Bind::new(4, Slot::GMotion, Use::Sampled),
];

/// Lane `k`'s resources, at bindings 8 + 8k onwards (shaders/reproject.comp's LANE_RESOURCES).
const fn lane_binds(k: u32) -> [Bind; 8] {
    let b = 8 + 8 * k;
    [
        Bind::new(b, Slot::HistoryPrev, Use::Sampled),
        // Every pixel is written: resampled history, or cleared where it is disoccluded.
        Bind::new(b + 1, Slot::History, Use::StorageWrite),
        Bind::new(b + 2, Slot::State, Use::StorageWrite),
        Bind::new(b + 3, Slot::Counters, Use::BufferReadWrite),
        Bind::new(b + 4, Slot::MomentsPrev, Use::Sampled),
        Bind::new(b + 5, Slot::Moments, Use::StorageWrite),
        Bind::new(b + 6, Slot::RegistrationPrev, Use::Sampled),
        Bind::new(b + 7, Slot::Registration, Use::StorageWrite),
    ]
}

const LANE_BINDS: [[Bind; 8]; MAX_LANES] = [lane_binds(0), lane_binds(1), lane_binds(2)];

/// The binding of lane `k`'s history (LANE_BINDS' `Slot::History`).
const fn history_binding(k: usize) -> u32 {
    8 + 8 * k as u32 + 1
}

/// The reprojection modules: one per lane count and combination of history formats
/// (shaders/reproject.comp's permutations).
fn modules() -> impl Iterator<Item = &'static ShaderModuleInfo> {
    shaders::ALL
        .iter()
        .copied()
        .filter(|m| m.name == "reproject.comp")
}

/// How many lanes `m` serves: its lanes are the history bindings it declares.
fn lanes_of(m: &ShaderModuleInfo) -> usize {
    (0..=MAX_LANES)
        .take_while(|&k| m.storage_format(1, history_binding(k)).is_some())
        .count()
}

/// The module whose lane k's history has `history_formats[k]`, chosen by its reflection (so
/// no name of a format is spelled here); `None` when no permutation has that combination.
fn module(history_formats: &[vk::Format]) -> Option<&'static ShaderModuleInfo> {
    modules().find(|m| {
        lanes_of(m) == history_formats.len()
            && history_formats
                .iter()
                .enumerate()
                .all(|(k, &f)| m.storage_format(1, history_binding(k)) == Some(f))
    })
}

fn binds(lanes: usize) -> Vec<Bind> {
    let mut v = SHARED.to_vec();
    for lane in &LANE_BINDS[..lanes] {
        v.extend_from_slice(lane);
    }
    v
}

/// Every permutation's layout for the reflection check.
pub fn layouts() -> Vec<PassLayout> {
    modules()
        .map(|m| {
            let n = lanes_of(m);
            PassLayout {
                pass: PassId::REPROJECT,
                modules: vec![m],
                declared: decl::layout(&binds(n)),
                binds: binds(n),
            }
        })
        .collect()
}

/// One lane's part of a frame: its push constants and whether it runs.
#[derive(Clone, Copy, Debug, Default)]
pub struct LaneFrame {
    /// The effect reprojects its history this frame.
    pub active: bool,
    pub history_valid: bool,
    /// log2 of the effect's work-block side.
    pub block_shift: u32,
    /// Refresh tile (x0, y0, x1, y1) [px]; empty = none.
    pub refresh_rect: [u32; 4],
    /// Which pixels a moving object takes the history from (`MovedReach` code, 0 = none).
    pub moved: u32,
    /// The screen-space reach's sampling radius, relative to the scene's bounding radius.
    pub reach_radius: f32,
    /// The camera came to rest: the lane's histories start re-accumulating
    /// (`TemporalConfig::reaccumulate`).
    pub reaccumulate: bool,
    /// A change reached the lane's values this frame (the light, a moving object): a
    /// re-accumulation under way ends, so the gated mean can see the change.
    pub stop_reaccumulating: bool,
}

/// The frame's push constants from each lane's part.
pub fn push(lanes: &[LaneFrame]) -> ReprojectPush {
    let lane = |k: usize| {
        lanes.get(k).map_or([0; 4], |l| {
            [
                l.active as u32,
                l.history_valid as u32,
                l.block_shift,
                l.moved,
            ]
        })
    };
    let rect = |k: usize| lanes.get(k).map_or([0; 4], |l| l.refresh_rect);
    let mask = |pick: fn(&LaneFrame) -> bool| {
        lanes
            .iter()
            .enumerate()
            .filter(|(_, l)| pick(l))
            .fold(0u32, |mask, (k, _)| mask | 1 << k)
    };
    let starts = mask(|l| l.reaccumulate);
    let stops = mask(|l| l.stop_reaccumulating);
    ReprojectPush {
        refresh_rect_0: rect(0),
        refresh_rect_1: rect(1),
        refresh_rect_2: rect(2),
        lane_0: lane(0),
        lane_1: lane(1),
        lane_2: lane(2),
        reaccumulate: [starts, stops, 0, 0],
        reach_radius: std::array::from_fn(|k| lanes.get(k).map_or(0.0, |l| l.reach_radius)),
    }
}

pub struct ReprojectPass {
    lanes: usize,
    module: &'static ShaderModuleInfo,
    pipeline: Pipeline,
    sets: [vk::DescriptorSet; 2],
}

impl ReprojectPass {
    /// The pass for one lane per temporal effect, lane k's history of `history_formats[k]`
    /// (1 ..= MAX_LANES lanes).
    pub fn new(
        ctx: &Arc<Context>,
        pool: &DescriptorPool,
        history_formats: &[vk::Format],
    ) -> Result<Self> {
        let lanes = history_formats.len();
        if lanes == 0 || lanes > MAX_LANES {
            return Err(Error::Config(format!(
                "the reprojection serves 1 to {MAX_LANES} temporal effects, not {lanes} \
                 (add a permutation to shaders/reproject.comp and a lane to LANE_BINDS)"
            )));
        }
        let module = module(history_formats).ok_or_else(|| {
            Error::Reflection(format!(
                "no reprojection permutation has lane histories {history_formats:?} (build.rs \
                 compiles one per combination of the *_HISTORY_FORMATs of \
                 shaders/include/shared_constants.glsl)"
            ))
        })?;
        let name = PassId::REPROJECT.name();
        let pipeline =
            Pipeline::compute_specialized(ctx, name, module, &decl::layout(&binds(lanes)), &[])?;
        let sets = parity_sets(pool, &pipeline, name)?;
        Ok(Self {
            lanes,
            module,
            pipeline,
            sets,
        })
    }

    /// Point both parities' sets at the G-buffer (`shared`) and each lane's resources, one
    /// resolver per lane in lane order (creation and resize, device idle).
    pub fn bind(&self, ctx: &Context, shared: &dyn Resolve, lanes: &[&dyn Resolve]) -> Result<()> {
        assert_eq!(lanes.len(), self.lanes, "one resolver per lane");
        let name = PassId::REPROJECT.name();
        for (parity, set) in self.sets.iter().enumerate() {
            let pass = (name, self.module);
            let mut w = decl::write_binds(SetWriter::new(), pass, SHARED, shared, parity)?;
            for (binds, res) in LANE_BINDS.iter().zip(lanes) {
                w = decl::write_binds(w, pass, binds, *res, parity)?;
            }
            w.write(ctx, *set);
        }
        Ok(())
    }

    /// Barriers for the G-buffer and the active lanes' resources, then one dispatch over every
    /// pixel. `lanes` pairs each lane's resolver with its part of the frame.
    pub fn record(
        &self,
        rec: &Recorder<'_>,
        tracker: &mut Tracker,
        frame: FrameSet,
        shared: &dyn Resolve,
        lanes: &[(&dyn Resolve, LaneFrame)],
        (width, height): (u32, u32),
    ) {
        let name = PassId::REPROJECT.name();
        decl::access(name, SHARED, shared, frame.parity, tracker);
        for (binds, (res, lane)) in LANE_BINDS.iter().zip(lanes) {
            if lane.active {
                decl::access(name, binds, *res, frame.parity, tracker);
            } else {
                // Left untouched, but the shader names its resources: they must be in the
                // layouts the set expects and synchronized as written, their contents kept.
                let kept = binds.map(|b| Bind::new(b.binding, b.slot, b.usage.keeping_contents()));
                decl::access(name, &kept, *res, frame.parity, tracker);
            }
        }
        tracker.flush(rec.device, rec.cmd);
        let mut frames = [LaneFrame::default(); MAX_LANES];
        for (f, (_, l)) in frames.iter_mut().zip(lanes) {
            *f = *l;
        }
        rec.bind(&self.pipeline, &[frame.set, self.sets[frame.parity]]);
        rec.push(&self.pipeline, &push(&frames[..lanes.len()]).to_bytes());
        rec.dispatch_2d(&self.pipeline, width, height);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_lane_count_has_a_module_for_the_effects_history_formats() {
        use crate::shaders::{
            AO_HISTORY_FORMAT, INDIRECT_HISTORY_FORMAT, SHADOW_HISTORY_FORMAT, SSDO_HISTORY_FORMAT,
        };
        let formats = [
            AO_HISTORY_FORMAT,
            SHADOW_HISTORY_FORMAT,
            INDIRECT_HISTORY_FORMAT,
            SSDO_HISTORY_FORMAT,
        ];
        // Every ordered choice of up to MAX_LANES effects' formats.
        for n in 1..=MAX_LANES {
            for pick in 0..formats.len().pow(n as u32) {
                let chosen: Vec<vk::Format> = (0..n)
                    .map(|k| formats[pick / formats.len().pow(k as u32) % formats.len()])
                    .collect();
                let m = module(&chosen).unwrap_or_else(|| panic!("no module for {chosen:?}"));
                assert_eq!(lanes_of(m), n);
            }
        }
        assert_eq!(layouts().len(), modules().count());
    }

    #[test]
    fn lanes_do_not_share_bindings() {
        let all = binds(MAX_LANES);
        let mut numbers: Vec<u32> = all.iter().map(|b| b.binding).collect();
        numbers.sort_unstable();
        numbers.dedup();
        assert_eq!(numbers.len(), all.len());
    }

    #[test]
    fn absent_lanes_push_inactive() {
        let p = push(&[LaneFrame {
            active: true,
            history_valid: true,
            block_shift: 4,
            refresh_rect: [1, 2, 3, 4],
            moved: 1,
            reach_radius: 0.25,
            reaccumulate: false,
            stop_reaccumulating: false,
        }]);
        assert_eq!(p.lane_0, [1, 1, 4, 1]);
        assert_eq!(p.reach_radius, [0.25, 0.0, 0.0, 0.0]);
        assert_eq!(p.refresh_rect_0, [1, 2, 3, 4]);
        assert_eq!(p.lane_1, [0; 4]);
        assert_eq!(p.lane_2, [0; 4]);
        assert_eq!(p.reaccumulate, [0; 4]);
    }

    #[test]
    fn reaccumulating_lanes_are_a_bit_mask() {
        let lane = |reaccumulate, stop_reaccumulating| LaneFrame {
            active: true,
            reaccumulate,
            stop_reaccumulating,
            ..Default::default()
        };
        let p = push(&[lane(true, false), lane(false, true), lane(true, false)]);
        assert_eq!(p.reaccumulate, [0b101, 0b010, 0, 0]);
    }
}
