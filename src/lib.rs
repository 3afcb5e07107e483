//! ssgi: screen-space global illumination on Vulkan (ash), reproducing and measuring three
//! papers: cached screen-space GI (Lin 2013), screen-space ambient and directional occlusion
//! (Szentandrási et al.), and incremental-PCA filtering of indirect light with subpixel
//! reconstruction antialiasing (Chen, Chang et al.). Each technique is an effect
//! (`effects/`) or a post stage (`post/`); docs/ARCHITECTURE.md draws the layers.

pub mod bench;
pub mod cli;
pub mod config;
pub mod effects;
pub mod error;
pub mod files;
pub mod frontend;
pub mod interrupt;
pub mod passes;
pub mod plot;
pub mod post;
pub mod reference;
pub mod renderer;
pub mod resources;
pub mod scene;
pub mod shaders;
pub mod stress;
pub mod sweep;
pub mod vk;

pub use error::{Error, Result};
