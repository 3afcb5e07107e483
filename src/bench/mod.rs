//! Benchmark runs: timing aggregation and reports, and the papers' tables (`ssgi table`):
//! measured rows, error against converged references, Markdown/JSON/CSV reports, PNG plots.

pub mod compare;
pub mod ground_truth;
pub mod measure;
pub mod metrics;
pub mod options;
pub mod output;
pub mod report;
pub mod sheet;
pub mod stats;
pub mod tables;
pub mod warmup;

pub use options::TableOptions;
pub use report::Report;
