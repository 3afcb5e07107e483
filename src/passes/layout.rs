//! What a pipeline of a pass declares, for the check against the shaders' reflection.

use super::decl::Bind;
use super::pass_id::PassId;
use crate::shaders::{DescriptorKind, ReflectedBinding, ShaderModuleInfo};

pub use super::decl::FRAME_BINDING;

pub(crate) const fn binding(set: u32, binding: u32, kind: DescriptorKind) -> ReflectedBinding {
    ReflectedBinding {
        set,
        binding,
        kind,
        count: 1,
    }
}

/// One pipeline of a pass: the modules it is built from, the layout the pass declares and
/// the resources behind it (what it reads and writes of other passes' outputs: the
/// dependency table is derived from them, `renderer::dependencies`).
pub struct PassLayout {
    pub pass: PassId,
    pub modules: Vec<&'static ShaderModuleInfo>,
    pub declared: Vec<ReflectedBinding>,
    pub binds: Vec<Bind>,
}
