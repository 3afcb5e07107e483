//! Charts drawn to PNG with `plotters`: line plots of per-frame series (line.rs) and scatter
//! plots of time against error (scatter.rs) with their Pareto front (pareto.rs). Text uses a font compiled
//! into the binary, so plots need no system fonts. Beside the stack: no Vulkan, no renderer.

pub mod line;
pub mod pareto;
pub mod scatter;

pub use line::{write_line_plot, LinePlot, Series};
pub use scatter::{write_scatter_plot, ScatterPlot, ScatterSeries};
