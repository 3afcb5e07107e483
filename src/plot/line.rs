//! PNG line plots with `plotters` (bitmap backend). Text uses a font compiled into the binary
//! (Hack, from `epaint_default_fonts`), so plots need no system fonts.

use crate::error::{Error, Result};
use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};
use std::path::Path;
use std::sync::OnceLock;

/// One line of a plot.
pub struct Series<'a> {
    pub name: &'a str,
    pub color: RGBColor,
    pub points: Vec<(f64, f64)>,
}

pub struct LinePlot<'a> {
    pub title: &'a str,
    pub x_label: &'a str,
    pub y_label: &'a str,
    pub series: Vec<Series<'a>>,
    pub size: (u32, u32),
}

pub const REUSE_COLOR: RGBColor = RGBColor(0x1f, 0x77, 0xb4);
pub const NO_REUSE_COLOR: RGBColor = RGBColor(0xd6, 0x27, 0x28);
pub const REUSE_AO_COLOR: RGBColor = RGBColor(0x6b, 0xae, 0xd6);
pub const NO_REUSE_AO_COLOR: RGBColor = RGBColor(0xfc, 0x92, 0x72);
pub const REUSE_INDIRECT_COLOR: RGBColor = RGBColor(0x2c, 0xa0, 0x2c);
pub const NO_REUSE_INDIRECT_COLOR: RGBColor = RGBColor(0xff, 0x7f, 0x0e);

/// Family name the embedded font is registered under; call [`font_ready`] before drawing text.
pub(crate) const FONT: &str = "sans-serif";

/// Registers the embedded font once per process; the result is cached.
pub(crate) fn font_ready() -> std::result::Result<(), String> {
    static REGISTERED: OnceLock<std::result::Result<(), String>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            register_font(FONT, FontStyle::Normal, epaint_default_fonts::HACK_REGULAR)
                .map_err(|_| "the embedded plot font is not a valid font".to_string())
        })
        .clone()
}

/// Draw `plot` and write it to `path` as PNG.
pub fn write_line_plot(plot: &LinePlot<'_>, path: &Path) -> Result<()> {
    let fail = |message: String| Error::ImageWrite {
        path: path.to_path_buf(),
        message,
    };
    font_ready().map_err(fail)?;
    let (w, h) = plot.size;
    let mut rgb = vec![0u8; w as usize * h as usize * 3];
    draw(plot, &mut rgb).map_err(fail)?;
    let rgba: Vec<u8> = rgb
        .chunks_exact(3)
        .flat_map(|p| [p[0], p[1], p[2], 255])
        .collect();
    crate::frontend::png::write_rgba8(path, w, h, &rgba)
}

/// Axis range [0, max] with a little headroom; a flat or empty series still gets a range.
fn upper(values: impl Iterator<Item = f64>) -> f64 {
    let max = values.filter(|v| v.is_finite()).fold(0.0f64, f64::max);
    if max > 0.0 {
        max * 1.08
    } else {
        1.0
    }
}

fn draw(plot: &LinePlot<'_>, rgb: &mut [u8]) -> std::result::Result<(), String> {
    let err = |e: &dyn std::fmt::Display| e.to_string();
    let root = BitMapBackend::with_buffer(rgb, plot.size).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let points = || plot.series.iter().flat_map(|s| s.points.iter());
    let x_max = upper(points().map(|p| p.0));
    let y_max = upper(points().map(|p| p.1));
    let mut chart = ChartBuilder::on(&root)
        .caption(plot.title, (FONT, 22))
        .margin(12)
        .x_label_area_size(42)
        .y_label_area_size(64)
        .build_cartesian_2d(0.0..x_max, 0.0..y_max)
        .map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .x_desc(plot.x_label)
        .y_desc(plot.y_label)
        .label_style((FONT, 14))
        .draw()
        .map_err(|e| err(&e))?;
    for s in &plot.series {
        let color = s.color;
        chart
            .draw_series(LineSeries::new(
                s.points.iter().copied().filter(|p| p.1.is_finite()),
                color.stroke_width(2),
            ))
            .map_err(|e| err(&e))?
            .label(s.name)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 24, y)], color.stroke_width(2))
            });
    }
    chart
        .configure_series_labels()
        .label_font((FONT, 14))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(|e| err(&e))?;
    root.present().map_err(|e| err(&e))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plot_has_lines_and_text() {
        let dir = std::env::temp_dir().join(format!("ssgi-plot-{}", std::process::id()));
        let path = dir.join("plot.png");
        let plot = LinePlot {
            title: "test plot",
            x_label: "frame",
            y_label: "ms",
            series: vec![
                Series {
                    name: "rising",
                    color: REUSE_COLOR,
                    points: (0..50).map(|i| (i as f64, i as f64)).collect(),
                },
                Series {
                    name: "flat",
                    color: NO_REUSE_COLOR,
                    points: (0..50).map(|i| (i as f64, 10.0)).collect(),
                },
            ],
            size: (480, 320),
        };
        write_line_plot(&plot, &path).unwrap();
        let img = image::open(&path).unwrap().to_rgb8();
        assert_eq!(img.dimensions(), (480, 320));
        let count = |c: RGBColor| img.pixels().filter(|p| p.0 == [c.0, c.1, c.2]).count();
        assert!(count(REUSE_COLOR) > 100, "rising line missing");
        assert!(count(NO_REUSE_COLOR) > 100, "flat line missing");
        // Text (title, labels, legend) leaves dark anti-aliased pixels that are neither line
        // colour nor white; the mesh lines are light grey.
        let dark = img.pixels().filter(|p| p.0.iter().all(|&v| v < 90)).count();
        assert!(dark > 200, "no text drawn ({dark} dark pixels)");
        std::fs::remove_dir_all(&dir).ok();
    }
}
