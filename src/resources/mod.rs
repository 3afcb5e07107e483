//! What passes and effects read and write, below both: the shared targets (G-buffer, RSM,
//! output), the scene on the GPU, and the temporal machinery every cached effect shares (its
//! history, moments and registration pairs, per-pixel state, counters and work lists, refresh
//! schedule), and the seeded randomness they draw from (`random.rs`).

pub mod counters;
pub mod random;
pub mod scene_gpu;
pub mod targets;
pub mod temporal;
pub mod temporal_effect;
