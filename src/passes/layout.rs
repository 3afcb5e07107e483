//! What a pipeline of a pass declares, for the check against the shaders' reflection.

use super::pass_id::PassId;
use crate::shaders::{DescriptorKind, ReflectedBinding, ShaderModuleInfo};

/// The per-frame uniform buffer every pass reads (set 0, binding 0).
pub const FRAME_BINDING: ReflectedBinding = ReflectedBinding {
    set: 0,
    binding: 0,
    kind: DescriptorKind::StorageBuffer,
    count: 1,
};

pub(crate) const fn binding(set: u32, binding: u32, kind: DescriptorKind) -> ReflectedBinding {
    ReflectedBinding {
        set,
        binding,
        kind,
        count: 1,
    }
}

/// One pipeline of a pass: the modules it is built from and the layout the pass declares.
pub struct PassLayout {
    pub pass: PassId,
    pub modules: Vec<&'static ShaderModuleInfo>,
    pub declared: Vec<ReflectedBinding>,
}
