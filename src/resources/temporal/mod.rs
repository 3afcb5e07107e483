//! CPU side of the temporal machinery: the tiled-refresh schedule (Nehab et al. 2007) in
//! `refresh_schedule.rs`, and its cost and budget per effect sampling in `refresh_budget.rs`.
//! The seeded generator and the SSAO rotation texture are in `resources/random.rs`.

mod refresh_budget;
mod refresh_schedule;

pub use refresh_budget::{budget_tile, tile_evaluations, Sampling};
pub use refresh_schedule::{RefreshRect, RefreshSchedule};
