//! PNG scatter plots with `plotters` for `ssgi sweep`: one marker per renderer configuration
//! (GPU time against error), one colour and marker shape per series, and the Pareto front as
//! a staircase. Text uses the embedded font from [`super::line`], so no system fonts are needed.

use super::line::{font_ready, FONT};
use crate::error::{Error, Result};
use plotters::coord::ranged1d::{Ranged, ValueFormatter};
use plotters::coord::types::RangedCoordf64;
use plotters::element::{Drawable, PointCollection};
use plotters::prelude::*;
use std::ops::Range;
use std::path::Path;

/// One group of points, e.g. all configurations of one technique.
pub struct ScatterSeries<'a> {
    pub name: &'a str,
    pub points: Vec<(f64, f64)>,
}

pub struct ScatterPlot<'a> {
    pub title: &'a str,
    pub x_label: &'a str,
    pub y_label: &'a str,
    pub series: Vec<ScatterSeries<'a>>,
    /// Vertices of the Pareto front (e.g. from `pareto::front_polyline`), drawn as a
    /// staircase; any order, NaNs skipped.
    pub front: Vec<(f64, f64)>,
    /// Logarithmic y axis. Errors span decades, but a configuration can also reach zero error
    /// (e.g. the reference itself), which a log axis cannot show: y values <= 0 are then drawn
    /// at the smallest positive y (clamped, so the point stays visible at the bottom) and the
    /// title says so; with no positive y at all the axis falls back to linear, also noted.
    /// Values more than 250 decades below the largest are clamped the same way, since the
    /// log axis cannot span more.
    pub log_y: bool,
    /// Width and height in pixels; each must be at least [`MIN_SIDE`].
    pub size: (u32, u32),
}

/// Smallest accepted width or height: below this the axis labels leave no room for the chart.
pub const MIN_SIDE: u32 = 64;

/// Series colours (matplotlib's tab10): ten hues that stay distinguishable on white.
pub const PALETTE: [RGBColor; 10] = [
    RGBColor(0x1f, 0x77, 0xb4),
    RGBColor(0xff, 0x7f, 0x0e),
    RGBColor(0x2c, 0xa0, 0x2c),
    RGBColor(0xd6, 0x27, 0x28),
    RGBColor(0x94, 0x67, 0xbd),
    RGBColor(0x8c, 0x56, 0x4b),
    RGBColor(0xe3, 0x77, 0xc2),
    RGBColor(0x7f, 0x7f, 0x7f),
    RGBColor(0xbc, 0xbd, 0x22),
    RGBColor(0x17, 0xbe, 0xcf),
];

/// The Pareto front: dark, so it reads as a reference line over the coloured markers.
pub const FRONT_COLOR: RGBColor = RGBColor(0x20, 0x20, 0x20);

/// Coordinates beyond this magnitude are skipped like NaN: padding them would overflow to
/// infinity, and no time or error of interest is that large.
const MAX_ABS: f64 = 1e300;

/// Smallest y a log axis treats as positive; smaller (subnormal) values would put the axis
/// bound at zero after padding.
const MIN_LOG: f64 = 1e-300;

/// Most decades a log axis spans before padding: plotters' log ticks divide the bounds, and
/// past ~308 decades that overflows to infinity and its tick loop never ends.
const MAX_DECADES: f64 = 250.0;

#[derive(Clone, Copy)]
enum Marker {
    Circle,
    Square,
    Triangle,
    Cross,
    Ring,
}

const MARKERS: [Marker; 5] = [
    Marker::Circle,
    Marker::Square,
    Marker::Triangle,
    Marker::Cross,
    Marker::Ring,
];

/// Colour and marker of series `i`. The marker also advances each time the colours wrap, so
/// the first 50 series all get distinct (colour, marker) pairs.
fn style_of(i: usize) -> (RGBColor, Marker) {
    let n = PALETTE.len();
    (PALETTE[i % n], MARKERS[(i + i / n) % MARKERS.len()])
}

/// Draw `plot` and write it to `path` as PNG.
pub fn write_scatter_plot(plot: &ScatterPlot<'_>, path: &Path) -> Result<()> {
    let fail = |message: String| Error::ImageWrite {
        path: path.to_path_buf(),
        message,
    };
    let (w, h) = plot.size;
    if w < MIN_SIDE || h < MIN_SIDE {
        return Err(fail(format!(
            "plot size {w}x{h} is below the minimum {MIN_SIDE}x{MIN_SIDE}"
        )));
    }
    font_ready().map_err(fail)?;
    let pixels = w as usize * h as usize;
    let mut rgb = vec![0u8; pixels * 3];
    draw(plot, &mut rgb).map_err(fail)?;
    let rgba: Vec<u8> = rgb
        .chunks_exact(3)
        .flat_map(|p| [p[0], p[1], p[2], 255])
        .collect();
    crate::frontend::png::write_rgba8(path, w, h, &rgba)
}

fn drawable(p: &(f64, f64)) -> bool {
    p.0.is_finite() && p.1.is_finite() && p.0.abs() <= MAX_ABS && p.1.abs() <= MAX_ABS
}

/// Linear axis range over `values`, padded by 6% of the span; a single value gets ±10% of
/// itself (±1 at zero) and no values give 0..1, so plotters always has a non-empty range.
fn linear_range(values: impl Iterator<Item = f64>) -> Range<f64> {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    if lo > hi {
        return 0.0..1.0;
    }
    let pad = if hi > lo {
        (hi - lo) * 0.06
    } else if lo != 0.0 {
        lo.abs() * 0.1
    } else {
        1.0
    };
    (lo - pad)..(hi + pad)
}

/// Log axis range over positive `values`, padded by 6% of the span in decades (a third of a
/// decade around a single value), bounds kept within f64's normal range.
fn log_range(values: impl Iterator<Item = f64>) -> Range<f64> {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v.log10()), hi.max(v.log10()))
    });
    if lo > hi {
        return 0.1..10.0;
    }
    let pad = if hi > lo { (hi - lo) * 0.06 } else { 1.0 / 3.0 };
    let exp = |e: f64| 10f64.powf(e.clamp(-307.0, 307.0));
    exp(lo - pad)..exp(hi + pad)
}

/// What the plot shows after filtering and the log-axis decision.
struct Layout {
    title: String,
    x: Range<f64>,
    /// `Some` holds the log range, `None` means a linear y axis with range `y`.
    y_log: Option<Range<f64>>,
    y: Range<f64>,
    series: Vec<Vec<(f64, f64)>>,
    front: Vec<(f64, f64)>,
}

impl Layout {
    fn new(plot: &ScatterPlot<'_>) -> Self {
        let clean = |points: &[(f64, f64)]| -> Vec<(f64, f64)> {
            points.iter().copied().filter(drawable).collect()
        };
        let mut series: Vec<Vec<(f64, f64)>> =
            plot.series.iter().map(|s| clean(&s.points)).collect();
        let mut front = clean(&plot.front);
        let all = || series.iter().flatten().chain(&front);
        let max_y = all().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max);
        let floor = MIN_LOG.max(max_y * 10f64.powf(-MAX_DECADES));
        let min_positive = all()
            .map(|p| p.1)
            .filter(|&y| y >= floor)
            .fold(f64::INFINITY, f64::min);
        let mut title = plot.title.to_string();
        let mut log = false;
        if plot.log_y {
            if min_positive.is_finite() {
                log = true;
                if all().any(|p| p.1 < floor) {
                    let what = if all().all(|p| p.1 <= 0.0 || p.1 >= floor) {
                        "y <= 0"
                    } else {
                        "y <= 0 or tiny"
                    };
                    title.push_str(&format!(" ({what} drawn at {min_positive:.3e})"));
                    for p in series.iter_mut().flatten().chain(&mut front) {
                        p.1 = p.1.max(min_positive);
                    }
                }
            } else {
                title.push_str(" (linear y: no positive values)");
            }
        }
        let all = || series.iter().flatten().chain(&front);
        let x = linear_range(all().map(|p| p.0));
        let y = linear_range(all().map(|p| p.1));
        let y_log = log.then(|| log_range(all().map(|p| p.1)));
        front.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
        Layout {
            title,
            x,
            y_log,
            y,
            series,
            front,
        }
    }
}

/// Tick label with at most 6 decimals, or scientific notation outside 1e-3..1e5, so extreme
/// ranges do not print hundreds of digits and float noise (0.30000000000000004) is cut off.
fn tick_label(v: f64) -> String {
    let trim = |s: String| {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    };
    if v == 0.0 {
        "0".to_string()
    } else if (1e-3..1e5).contains(&v.abs()) {
        trim(format!("{v:.6}"))
    } else {
        let s = format!("{v:.3e}");
        match s.split_once('e') {
            Some((mantissa, exp)) => format!("{}e{exp}", trim(mantissa.to_string())),
            None => s,
        }
    }
}

/// Log-axis tick label: plotters puts a tick at every 1..9 × 10^k, which crowds the top of
/// each decade, so only 1, 2 and 5 × 10^k are labelled (the grid line stays for the rest).
fn log_tick_label(v: f64) -> String {
    let mantissa = v / 10f64.powf(v.log10().floor());
    if [1.0, 2.0, 5.0, 10.0]
        .iter()
        .any(|m| (mantissa - m).abs() < 1e-6 * m)
    {
        tick_label(v)
    } else {
        String::new()
    }
}

/// The front as a staircase for minimisation: from each vertex right at its y to the next
/// vertex's x, then down to that vertex. Everything above and right of it is dominated.
fn staircase(front: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut line = Vec::with_capacity(front.len() * 2);
    for (i, &p) in front.iter().enumerate() {
        if i > 0 {
            line.push((p.0, front[i - 1].1));
        }
        line.push(p);
    }
    line
}

fn draw(plot: &ScatterPlot<'_>, rgb: &mut [u8]) -> std::result::Result<(), String> {
    let layout = Layout::new(plot);
    let root = BitMapBackend::with_buffer(rgb, plot.size).into_drawing_area();
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let mut builder = ChartBuilder::on(&root);
    builder
        .caption(&layout.title, (FONT, 22))
        .margin(12)
        .x_label_area_size(42)
        .y_label_area_size(72);
    let x = layout.x.clone();
    match &layout.y_log {
        Some(y) => {
            let chart = builder
                .build_cartesian_2d(x, y.clone().log_scale())
                .map_err(|e| e.to_string())?;
            fill(chart, plot, &layout, &|v| log_tick_label(*v), 0)?;
        }
        None => {
            let chart = builder
                .build_cartesian_2d(x, layout.y.clone())
                .map_err(|e| e.to_string())?;
            fill(chart, plot, &layout, &|v| tick_label(*v), 10)?;
        }
    }
    root.present().map_err(|e| e.to_string())
}

/// Mesh, markers, front and legend; generic over the y axis so linear and log share it. A log
/// axis already has a grid line at every 1..9 × 10^k, so it gets no extra light lines.
fn fill<'a, DB, Y>(
    mut chart: ChartContext<'a, DB, Cartesian2d<RangedCoordf64, Y>>,
    plot: &ScatterPlot<'_>,
    layout: &Layout,
    y_format: &dyn Fn(&f64) -> String,
    y_light_lines: usize,
) -> std::result::Result<(), String>
where
    DB: DrawingBackend + 'a,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let err = |e: &dyn std::fmt::Display| e.to_string();
    chart
        .configure_mesh()
        .x_desc(plot.x_label)
        .y_desc(plot.y_label)
        .label_style((FONT, 14))
        .x_label_formatter(&|v| tick_label(*v))
        .y_label_formatter(y_format)
        .y_max_light_lines(y_light_lines)
        .draw()
        .map_err(|e| err(&e))?;
    for (i, (s, points)) in plot.series.iter().zip(&layout.series).enumerate() {
        let (color, marker) = style_of(i);
        let (fill, stroke) = (color.filled(), color.stroke_width(2));
        let r = 4;
        match marker {
            Marker::Circle => marked(&mut chart, points, s.name, move || {
                Circle::new((0, 0), r, fill)
            }),
            Marker::Ring => marked(&mut chart, points, s.name, move || {
                Circle::new((0, 0), r, stroke)
            }),
            Marker::Square => marked(&mut chart, points, s.name, move || {
                Rectangle::new([(-r, -r), (r, r)], fill)
            }),
            Marker::Triangle => marked(&mut chart, points, s.name, move || {
                TriangleMarker::new((0, 0), r + 1, fill)
            }),
            Marker::Cross => marked(&mut chart, points, s.name, move || {
                Cross::new((0, 0), r, stroke)
            }),
        }?;
    }
    if !layout.front.is_empty() {
        chart
            .draw_series(LineSeries::new(
                staircase(&layout.front),
                FRONT_COLOR.stroke_width(2),
            ))
            .map_err(|e| err(&e))?
            .label("Pareto front")
            .legend(|(x, y)| {
                PathElement::new(vec![(x, y), (x + 24, y)], FRONT_COLOR.stroke_width(2))
            });
        // Rings mark the optimal points themselves; a one-point front has no visible line.
        chart
            .draw_series(
                layout
                    .front
                    .iter()
                    .map(|&p| EmptyElement::at(p) + Circle::new((0, 0), 7, FRONT_COLOR)),
            )
            .map_err(|e| err(&e))?;
    }
    if !plot.series.is_empty() || !layout.front.is_empty() {
        chart
            .configure_series_labels()
            .label_font((FONT, 14))
            .background_style(WHITE.mix(0.75))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(|e| err(&e))?;
    }
    Ok(())
}

/// One series of markers plus its legend entry. Generic over the marker shape (built at the
/// pixel offset (0, 0) and placed with `EmptyElement`), because plotters' boxed `DynElement`
/// would demand a `'static` backend.
fn marked<'a, DB, Y, S>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<RangedCoordf64, Y>>,
    points: &[(f64, f64)],
    name: &str,
    shape: impl Fn() -> S + 'a,
) -> std::result::Result<(), String>
where
    DB: DrawingBackend + 'a,
    Y: Ranged<ValueType = f64>,
    S: Drawable<DB> + 'a,
    for<'b> &'b S: PointCollection<'b, (i32, i32)>,
{
    chart
        .draw_series(points.iter().map(|&p| EmptyElement::at(p) + shape()))
        .map_err(|e| e.to_string())?
        .label(name)
        .legend(move |at| EmptyElement::at(at) + shape());
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::pareto::{front_polyline, pareto_front};

    fn temp_png(name: &str) -> std::path::PathBuf {
        std::env::temp_dir()
            .join(format!("ssgi-scatter-{}", std::process::id()))
            .join(format!("{name}.png"))
    }

    fn plot<'a>(
        series: Vec<ScatterSeries<'a>>,
        front: Vec<(f64, f64)>,
        log_y: bool,
    ) -> ScatterPlot<'a> {
        ScatterPlot {
            title: "sweep",
            x_label: "GPU ms",
            y_label: "error",
            series,
            front,
            log_y,
            size: (480, 360),
        }
    }

    /// Writes `plot`, decodes it and checks its size and that something was drawn.
    fn write_and_check(plot: &ScatterPlot<'_>, name: &str) -> image::RgbImage {
        let path = temp_png(name);
        write_scatter_plot(plot, &path).unwrap();
        let img = image::open(&path).unwrap().to_rgb8();
        std::fs::remove_file(&path).ok();
        assert_eq!(img.dimensions(), plot.size);
        let first = img.get_pixel(0, 0);
        assert!(img.pixels().any(|p| p != first), "{name}: uniform image");
        img
    }

    fn count(img: &image::RgbImage, c: RGBColor) -> usize {
        img.pixels().filter(|p| p.0 == [c.0, c.1, c.2]).count()
    }

    #[test]
    fn scatter_has_markers_front_and_text() {
        let mut rng = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            (rng >> 11) as f64 / (1u64 << 53) as f64
        };
        let series: Vec<ScatterSeries> = ["a", "b", "c"]
            .iter()
            .map(|&name| ScatterSeries {
                name,
                points: (0..30)
                    .map(|_| (1.0 + 9.0 * next(), (-3.0 * next()).exp()))
                    .collect(),
            })
            .collect();
        let all: Vec<(f64, f64)> = series.iter().flat_map(|s| s.points.clone()).collect();
        let front = front_polyline(&all, &pareto_front(&all));
        for log_y in [false, true] {
            let p = plot(
                series
                    .iter()
                    .map(|s| ScatterSeries {
                        name: s.name,
                        points: s.points.clone(),
                    })
                    .collect(),
                front.clone(),
                log_y,
            );
            let img = write_and_check(&p, &format!("full-{log_y}"));
            for (i, &color) in PALETTE.iter().take(3).enumerate() {
                assert!(count(&img, color) > 30, "series {i} missing (log {log_y})");
            }
            assert!(
                count(&img, FRONT_COLOR) > 100,
                "front missing (log {log_y})"
            );
        }
    }

    #[test]
    fn many_series_cycle_styles() {
        let pairs: Vec<_> = (0..50)
            .map(|i| {
                let (c, m) = style_of(i);
                (c, m as usize)
            })
            .collect();
        for i in 0..pairs.len() {
            for j in 0..i {
                assert!(pairs[i] != pairs[j], "series {i} and {j} look the same");
            }
        }
        let names: Vec<String> = (0..23).map(|i| format!("s{i}")).collect();
        let series = names
            .iter()
            .enumerate()
            .map(|(i, name)| ScatterSeries {
                name,
                points: vec![(i as f64, 1.0 + i as f64)],
            })
            .collect();
        write_and_check(&plot(series, vec![], true), "many");
    }

    #[test]
    fn degenerate_inputs_still_write_png() {
        let nan = f64::NAN;
        let inf = f64::INFINITY;
        type Case = (&'static str, Vec<Vec<(f64, f64)>>, Vec<(f64, f64)>);
        let cases: Vec<Case> = vec![
            ("no-series", vec![], vec![]),
            ("empty-series", vec![vec![], vec![]], vec![]),
            ("one-point", vec![vec![(2.0, 0.5)]], vec![(2.0, 0.5)]),
            ("one-zero-point", vec![vec![(0.0, 0.0)]], vec![(0.0, 0.0)]),
            ("all-equal", vec![vec![(3.0, 3.0); 10]], vec![(3.0, 3.0)]),
            (
                "nans",
                vec![vec![(nan, 1.0), (1.0, nan), (nan, nan), (inf, 1.0)]],
                vec![(nan, nan)],
            ),
            (
                "mixed-nans",
                vec![vec![(nan, 1.0), (1.0, 2.0), (2.0, 1.0)]],
                vec![(1.0, 2.0), (nan, 0.0), (2.0, 1.0)],
            ),
            (
                "zeros",
                vec![vec![(1.0, 0.0), (2.0, 0.0)]],
                vec![(1.0, 0.0)],
            ),
            (
                "zeros-and-positive",
                vec![vec![(1.0, 0.0), (2.0, 0.01), (3.0, 10.0)]],
                vec![(1.0, 0.0)],
            ),
            (
                "negative",
                vec![vec![(-1.0, -5.0), (-2.0, -0.5), (4.0, 2.0)]],
                vec![(-2.0, -5.0)],
            ),
            (
                "huge",
                vec![vec![(1e300, 1e300), (-1e300, 1e-300), (f64::MAX, 1.0)]],
                vec![],
            ),
            (
                "tiny",
                vec![vec![(5e-324, 5e-324), (1e-310, 1e-320)]],
                vec![],
            ),
            ("decades", vec![vec![(1.0, 1e-300), (2.0, 1e300)]], vec![]),
            (
                "decades-and-zero",
                vec![vec![(1.0, 1e-300), (2.0, 1e300), (3.0, 0.0)]],
                vec![(1.0, 1e-300)],
            ),
        ];
        for (name, series, front) in cases {
            for log_y in [false, true] {
                let series = series
                    .iter()
                    .map(|points| ScatterSeries {
                        name,
                        points: points.clone(),
                    })
                    .collect();
                write_and_check(
                    &plot(series, front.clone(), log_y),
                    &format!("{name}-{log_y}"),
                );
            }
        }
    }

    /// Random extreme inputs (magnitudes across f64's whole range, signs, zeros, NaNs, near-equal
    /// values) must neither panic nor hang plotters' tick computation.
    #[test]
    fn random_extremes_draw() {
        let mut state = 0x853c_49e6_748f_ea9bu64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        font_ready().unwrap();
        for case in 0..300 {
            let base = f64::from_bits(next()); // any bit pattern: NaN, inf, subnormal, huge
            let value = |next: &mut dyn FnMut() -> u64| match next() % 6 {
                0 => f64::from_bits(next()),
                1 => 0.0,
                2 => base,
                3 => base * (1.0 + (next() % 4) as f64 * f64::EPSILON),
                4 => (next() % 1000) as f64 * 1e-3,
                _ => 10f64.powi((next() % 600) as i32 - 300),
            };
            let n = (next() % 12) as usize;
            let points: Vec<(f64, f64)> = (0..n)
                .map(|_| (value(&mut next), value(&mut next)))
                .collect();
            let front: Vec<(f64, f64)> = points.iter().copied().take(3).collect();
            for log_y in [false, true] {
                let mut p = plot(
                    vec![ScatterSeries {
                        name: "r",
                        points: points.clone(),
                    }],
                    front.clone(),
                    log_y,
                );
                p.size = (160, 120);
                let mut rgb = vec![0u8; 160 * 120 * 3];
                let result = draw(&p, &mut rgb);
                assert!(result.is_ok(), "case {case} {points:?}: {result:?}");
            }
        }
    }

    #[test]
    fn log_notes_in_title() {
        let with = |points: Vec<(f64, f64)>| {
            let p = plot(vec![ScatterSeries { name: "s", points }], vec![], true);
            Layout::new(&p)
        };
        let zeros = with(vec![(1.0, 0.0), (2.0, 0.25)]);
        assert!(zeros.y_log.is_some() && zeros.title.contains("y <= 0"));
        assert_eq!(zeros.series[0], vec![(1.0, 0.25), (2.0, 0.25)]);
        let none_positive = with(vec![(1.0, 0.0), (2.0, -1.0)]);
        assert!(none_positive.y_log.is_none() && none_positive.title.contains("linear"));
        let decades = with(vec![(1.0, 1e-280), (2.0, 1e10), (3.0, 1e-200)]);
        assert!(decades.title.contains("tiny"), "{}", decades.title);
        assert_eq!(decades.series[0][0], (1.0, 1e-200));
        let fine = with(vec![(1.0, 0.5), (2.0, 0.25)]);
        assert!(fine.y_log.is_some() && fine.title == "sweep");
    }

    #[test]
    fn staircase_steps_down() {
        assert_eq!(
            staircase(&[(1.0, 3.0), (2.0, 2.0), (4.0, 1.0)]),
            vec![(1.0, 3.0), (2.0, 3.0), (2.0, 2.0), (4.0, 2.0), (4.0, 1.0)]
        );
    }

    #[test]
    fn tick_labels_are_short() {
        assert_eq!(tick_label(0.0), "0");
        assert_eq!(tick_label(0.30000000000000004), "0.3");
        assert_eq!(tick_label(2.0), "2");
        assert_eq!(tick_label(-1.25), "-1.25");
        assert_eq!(tick_label(1e300), "1e300");
        assert_eq!(tick_label(2.5e-7), "2.5e-7");
        assert_eq!(log_tick_label(0.2), "0.2");
        assert_eq!(log_tick_label(0.9000000000001), "");
        assert_eq!(log_tick_label(1000.0), "1000");
        assert_eq!(log_tick_label(f64::NAN), "");
    }

    #[test]
    fn refuses_tiny_size() {
        let mut p = plot(vec![], vec![], false);
        p.size = (0, 0);
        assert!(write_scatter_plot(&p, &temp_png("tiny-size")).is_err());
    }
}
