//! Every pass and pipeline a frame may have, from the three places that declare them: the
//! frame's own passes (`passes`), the effects' registry and the post stages' registry.

use crate::passes::{PassId, PassLayout};

/// The frame's passes recorded after the effects' and before the post stages'.
const BEFORE_POST: [PassId; 1] = [PassId::COMPOSITE];

/// Every pass a frame may record, in recording order: the frame's own before the effects',
/// each effect's in registry order, the composite, then each post stage's. The timing
/// report's rows, the skip report and the dependency table follow it.
pub fn all_passes() -> Vec<PassId> {
    let mut v: Vec<PassId> = PassId::BEFORE_EFFECTS.to_vec();
    v.extend(crate::effects::effect_passes());
    v.extend(BEFORE_POST);
    v.extend(crate::post::REGISTRY.iter().flat_map(|r| r.passes));
    v
}

/// The pipelines every configuration may build outside the effects: the frame's own and the
/// post stages'.
pub fn frame_layouts() -> Vec<PassLayout> {
    let mut v = crate::passes::frame_layouts();
    v.extend(crate::post::all_layouts());
    v
}

/// Every pipeline of every pass, for the reflection check (also done when each pipeline is
/// built).
pub fn all_layouts() -> Vec<PassLayout> {
    let mut v = frame_layouts();
    v.extend(crate::effects::effect_layouts());
    v
}
