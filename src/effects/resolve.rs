//! The one place slots become images: shared targets (G-buffer, RSM, output) from `Targets`,
//! the temporal history/state/counters from the effect's `TemporalEffect`, and the images and
//! buffers the effect owns by name (`Slot::Own`, `Slot::OwnBuffer`).

use crate::passes::decl::{Resolve, Slot};
use crate::resources::targets::{Target, Targets};
use crate::resources::temporal_effect::TemporalEffect;
use crate::vk::{Buffer, Image};

/// An effect's view of the frame's resources.
pub struct EffectResources<'a> {
    pub targets: &'a Targets,
    pub temporal: Option<&'a TemporalEffect>,
    /// Each `Slot::Own` the effect's passes bind, with its image per parity (most effect
    /// images are not ping-ponged: both the same).
    pub own: &'a [(Slot, [&'a Image; 2])],
    /// Each `Slot::OwnBuffer`, with its buffer.
    pub own_buffers: &'a [(Slot, &'a Buffer)],
}

/// The shared targets every pass may read, for a parity (the images come from `Targets::get`,
/// the one place that knows which image backs a shared target).
pub fn shared_target(t: &Targets, slot: Slot, parity: usize) -> Option<&Image> {
    let target = match slot {
        Slot::GPosition => Target::GPosition,
        Slot::GPositionPrev => Target::GPositionHistory,
        Slot::GNormal => Target::GNormal,
        Slot::GNormalPrev => Target::GNormalHistory,
        Slot::GAlbedo => Target::GAlbedo,
        Slot::GMotion => Target::GMotion,
        Slot::GDepth => Target::GDepth,
        Slot::RsmPosition => Target::RsmPosition,
        Slot::RsmNormal => Target::RsmNormal,
        Slot::RsmFlux => Target::RsmFlux,
        Slot::RsmDepth => Target::RsmDepth,
        Slot::Output => Target::Output,
        Slot::DirectLight => Target::Direct,
        Slot::Shaded => Target::Shaded,
        Slot::SubPosition(i) => return subpixels(t)?.position.get(i as usize),
        Slot::SubNormal(i) => return subpixels(t)?.normal.get(i as usize),
        Slot::SubDepth => return subpixels(t).map(|s| &s.depth),
        Slot::GVisibility => return t.gbuffer.visibility.as_ref(),
        _ => return None,
    };
    t.get(target, parity)
}

fn subpixels(t: &Targets) -> Option<&crate::resources::targets::Subpixels> {
    t.antialias.as_ref()?.subpixels.as_ref()
}

impl Resolve for EffectResources<'_> {
    fn image(&self, slot: Slot, parity: usize) -> Option<&Image> {
        match slot {
            Slot::History => self.temporal.map(|e| e.history.current(parity)),
            Slot::HistoryPrev => self.temporal.map(|e| e.history.previous(parity)),
            Slot::Moments => self.temporal.map(|e| e.moments.current(parity)),
            Slot::MomentsPrev => self.temporal.map(|e| e.moments.previous(parity)),
            Slot::Registration => self.temporal.map(|e| e.registration.current(parity)),
            Slot::RegistrationPrev => self.temporal.map(|e| e.registration.previous(parity)),
            Slot::State => self.temporal.map(|e| &e.state),
            Slot::Own(_) => self
                .own
                .iter()
                .find(|(s, _)| *s == slot)
                .map(|(_, pair)| pair[parity]),
            _ => shared_target(self.targets, slot, parity),
        }
    }

    fn buffer(&self, slot: Slot) -> Option<&Buffer> {
        match slot {
            Slot::Counters => self.temporal.map(|e| &e.counters),
            Slot::OwnBuffer(_) => self
                .own_buffers
                .iter()
                .find(|(s, _)| *s == slot)
                .map(|(_, b)| *b),
            _ => None,
        }
    }
}
