//! Benchmark runs: timing aggregation and reports, and the papers' tables (`ssgi table`):
//! measured rows, error against converged references, Markdown/JSON/CSV reports, PNG plots.

pub mod aa_edges;
pub mod compare;
pub mod csv;
pub mod decimate;
pub mod ground_truth;
pub mod markdown;
pub mod measure;
pub mod metrics;
pub mod options;
pub mod output;
pub mod pareto;
pub mod paths;
pub mod plot;
pub mod report;
pub mod reuse_rows;
pub mod reuse_tables;
pub mod scatter;
pub mod stats;
pub mod stress;
pub mod sweep;
pub mod sweep_keys;
pub mod sweep_report;
pub mod szentandrasi;
pub mod table41;
pub mod table_chang;
pub mod table_chang_flicker;
pub mod table_dynamic;
pub mod table_report;
pub mod table_run;
pub mod table_sraa;
pub mod table_szentandrasi;
pub mod thesis;
pub mod walkthrough;
pub mod warmup;

pub use options::TableOptions;
pub use report::Report;
