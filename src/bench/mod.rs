//! Benchmark runs: timing aggregation and reports.

pub mod compare;
pub mod report;
pub mod stats;

pub use report::Report;
