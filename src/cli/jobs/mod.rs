//! The subcommands' work, one file each; `common.rs` holds what they share.

mod bench;
mod common;
mod reference;
mod render;
mod stress;
mod sweep;
mod table;
mod view;

pub use bench::bench;
pub use reference::reference;
pub use render::render;
pub use stress::stress;
pub use sweep::sweep;
pub use table::table;
pub use view::view;
