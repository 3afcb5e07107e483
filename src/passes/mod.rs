//! Passes: the declaration every pass is made from (`decl`), the shared compute and raster
//! helpers, and the passes every frame runs whatever the effects (light view, G-buffer,
//! reprojection, composite). The effects' own passes live in `src/effects/`, the antialiasing's
//! in `src/post/`. `PassId` names
//! are the rows of the timing report.

pub mod composite;
pub mod compute;
pub mod decl;
pub mod gbuffer;
pub mod layout;
pub mod light_view;
pub mod pass_id;
pub mod raster;
pub mod reproject;

pub use layout::{PassLayout, FRAME_BINDING};
pub use pass_id::{Change, PassId};

/// Every pipeline of the passes every frame runs (the effects add theirs: see
/// `renderer::all_layouts`), for the reflection check (also done at pipeline creation).
pub fn frame_layouts() -> Vec<PassLayout> {
    let mut v = Vec::new();
    v.extend(light_view::layouts());
    v.extend(gbuffer::layouts());
    v.extend(reproject::layouts());
    v.extend(composite::layouts());
    v
}
