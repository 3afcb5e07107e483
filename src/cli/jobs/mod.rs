//! The subcommands' work, one file each; `common.rs` holds what they share.

mod bench;
mod common;
mod render;
mod table;
mod view;

pub use bench::bench;
pub use render::render;
pub use table::table;
pub use view::view;
