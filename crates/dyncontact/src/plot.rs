//! Plots (PNG or SVG, chosen by the file extension) with an embedded font, so no system
//! font library is needed.
//!
//! A figure is described by plain data ([`Panel`]s of [`Series`], or a [`Map`]); drawing it
//! also produces a [`FigureReport`] of what was drawn: the axes' ranges, for each series the
//! points inside and outside them and whether its legend entry and line were drawn, for each
//! map its scale per pixel in x and y. With `DYNCONTACT_PLOT_REPORT=FILE` in the environment
//! every figure appends its report to FILE as one JSON line; the CLI tests check them
//! (`tests/support/mod.rs`, `check_plot_report`) instead of looking at pixels.
//!
//! Rules every figure follows: lines are clipped to the plotting area (a segment leaving it
//! is cut at the frame; no stroke joins, whose mitres overshoot at sharp turns); the axes
//! hold every data point (reference curves such as a linear theory are clipped instead);
//! legends sit in a strip below the chart, never over the curves, and exist only for panels
//! of several series; a series with nothing visible is named in a note under the title
//! instead of a legend entry; maps keep equal scales in x and y; every figure is headed by
//! the scenario's name ([`set_scenario`]).

use std::io::Write;
use std::path::Path;
use std::sync::{Mutex, Once, OnceLock};

use anyhow::{Result, anyhow};
use plotters::coord::Shift;
use plotters::prelude::*;
pub use plotters::style::RGBColor;
use serde::Serialize;

use crate::output::write_atomic;

static FONT: Once = Once::new();
static SCENARIO: OnceLock<String> = OnceLock::new();
static REPORT_LOCK: Mutex<()> = Mutex::new(());

/// The environment variable naming the file that figure reports are appended to.
pub const REPORT_ENV: &str = "DYNCONTACT_PLOT_REPORT";

fn register_font() {
    FONT.call_once(|| {
        let _ = plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            dejavu::sans::regular(),
        );
    });
}

/// The scenario named in the heading of every figure of this run (set once, by `main`).
pub fn set_scenario(name: impl Into<String>) {
    let _ = SCENARIO.set(name.into());
}

fn scenario() -> &'static str {
    SCENARIO.get().map_or("", String::as_str)
}

/// How a series takes part in the axes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Role {
    /// Result data: the axes hold every finite point.
    #[default]
    Data,
    /// A reference curve (a theory, a load line): it does not set the axes and is clipped to
    /// them.
    Reference,
}

/// One line of a chart.
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
    pub role: Role,
}

impl Series {
    pub fn new(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            label: label.into(),
            points,
            role: Role::Data,
        }
    }

    /// A reference curve, clipped to the axes the data set.
    pub fn reference(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            role: Role::Reference,
            ..Series::new(label, points)
        }
    }

    /// A piecewise-constant quantity (one value per cell of width `width` centred at x)
    /// drawn as steps: each cell a horizontal stroke, joined by vertical risers to the next
    /// cell when it is adjacent (a gap between cells breaks the line).
    pub fn steps(label: impl Into<String>, cells: &[(f64, f64)], width: f64) -> Self {
        let mut points = Vec::with_capacity(2 * cells.len());
        let mut last_right: Option<f64> = None;
        for &(x, v) in cells {
            let (left, right) = (x - 0.5 * width, x + 0.5 * width);
            if let Some(r) = last_right
                && (left - r).abs() > 1e-6 * width.abs()
            {
                points.push((f64::NAN, f64::NAN));
            }
            points.push((left, v));
            points.push((right, v));
            last_right = Some(right);
        }
        Series::new(label, points)
    }
}

/// One chart of a figure.
pub struct Panel {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
}

/// What one series of a drawn panel showed.
#[derive(Serialize, Debug)]
pub struct SeriesReport {
    pub label: String,
    /// "data" or "reference".
    pub role: &'static str,
    pub points: usize,
    pub finite_points: usize,
    /// Finite points inside the axes' ranges.
    pub points_inside: usize,
    /// Finite points outside them (0 for data; reference curves are clipped).
    pub points_outside: usize,
    /// Line pieces (or single-point markers) drawn with a visible part inside the axes.
    pub drawn_pieces: usize,
    /// Whether the series has an entry in the legend.
    pub legend: bool,
    /// Its line colour (RGB) and stroke width in pixels.
    pub colour: [u8; 3],
    pub width: u32,
}

/// What one drawn panel showed.
#[derive(Serialize, Debug)]
pub struct PanelReport {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub x_range: [f64; 2],
    pub y_range: [f64; 2],
    pub series: Vec<SeriesReport>,
    /// The note under the title (series with nothing visible), if any.
    pub note: Option<String>,
    /// Why the panel was not plotted (values outside the plottable range), if it was not.
    pub skipped: Option<String>,
}

/// What one drawn map showed.
#[derive(Serialize, Debug)]
pub struct MapReport {
    pub title: String,
    pub grid: [usize; 2],
    /// The data's extent (the grid) and the axes' ranges.
    pub extent_x: [f64; 2],
    pub extent_y: [f64; 2],
    pub x_range: [f64; 2],
    pub y_range: [f64; 2],
    /// Pixels per unit along x and along y (equal for an undistorted map).
    pub pixels_per_unit: [f64; 2],
    /// "continuous" (colour bar) or "categorical" (legend of categories).
    pub scale: &'static str,
    /// Colour bar range, for a continuous scale.
    pub bar_range: Option<[f64; 2]>,
    /// Category labels with their cell counts (legend entries), for a categorical scale.
    pub categories: Vec<(String, usize)>,
    /// Cells drawn in the exterior colour (not part of the data scale).
    pub exterior_cells: usize,
}

/// What one figure file showed.
#[derive(Serialize, Debug)]
pub struct FigureReport {
    pub file: String,
    pub scenario: String,
    pub panels: Vec<PanelReport>,
    pub maps: Vec<MapReport>,
}

/// Appends the report to the file named by [`REPORT_ENV`], if set.
fn publish(report: &FigureReport) -> Result<()> {
    let Some(path) = std::env::var_os(REPORT_ENV) else {
        return Ok(());
    };
    let line = serde_json::to_string(report)?;
    let _guard = REPORT_LOCK.lock().unwrap_or_else(|e| e.into_inner());
    let mut f = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(&path)
        .map_err(|e| anyhow!("plot report {}: {e}", Path::new(&path).display()))?;
    writeln!(f, "{line}")?;
    Ok(())
}

/// Line colours in order (Tableau 10 reordered, then black and navy): twelve distinct colours,
/// so a panel of up to twelve series never repeats one (the sweep plots draw ten trains, the
/// envelope and the limit).
const COLOURS: [RGBColor; 12] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(0, 0, 0),
    RGBColor(0, 0, 128),
];

/// Largest magnitude a plotted value may have (beyond it the axis labels and the line
/// rasterisation lose meaning; such panels are skipped with a note).
const PLOT_MAX_MAGNITUDE: f64 = 1e100;
/// Points drawn per series at most: longer series are thinned by keeping each bucket's
/// minimum and maximum (peaks survive), which bounds the plotting time.
const PLOT_MAX_POINTS: usize = 8000;

/// The axis range of `values` with a 4 % margin (non-finite values ignored), or why the panel
/// cannot be plotted.
fn range_of(values: impl Iterator<Item = f64>) -> Result<(f64, f64), String> {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !lo.is_finite() {
        return Ok((0.0, 1.0));
    }
    let big = lo.abs().max(hi.abs());
    if big > PLOT_MAX_MAGNITUDE || (big > 0.0 && big < 1.0 / PLOT_MAX_MAGNITUDE) {
        return Err(format!(
            "values up to {big:.3e} in magnitude are outside the plottable range [1e-100, 1e100]"
        ));
    }
    if hi - lo <= 1e-12 * big {
        let pad = if big == 0.0 { 1.0 } else { 0.05 * big };
        return Ok((lo - pad, hi + pad));
    }
    let pad = 0.04 * (hi - lo);
    Ok((lo - pad, hi + pad))
}

/// The finite runs of a series (a NaN or infinity breaks the line), each thinned to at most
/// [`PLOT_MAX_POINTS`] points by per-bucket minimum and maximum.
fn drawable_segments(points: &[(f64, f64)]) -> Vec<Vec<(f64, f64)>> {
    let mut segments = Vec::new();
    for run in points.split(|(x, y)| !(x.is_finite() && y.is_finite())) {
        if run.is_empty() {
            continue;
        }
        if run.len() <= PLOT_MAX_POINTS {
            segments.push(run.to_vec());
            continue;
        }
        let buckets = PLOT_MAX_POINTS / 2;
        let size = run.len().div_ceil(buckets);
        let mut thin = Vec::with_capacity(2 * buckets + 1);
        for chunk in run.chunks(size) {
            let (mut i_lo, mut i_hi) = (0, 0);
            for (i, p) in chunk.iter().enumerate() {
                if p.1 < chunk[i_lo].1 {
                    i_lo = i;
                }
                if p.1 > chunk[i_hi].1 {
                    i_hi = i;
                }
            }
            thin.push(chunk[i_lo.min(i_hi)]);
            if i_lo != i_hi {
                thin.push(chunk[i_lo.max(i_hi)]);
            }
        }
        thin.push(run[run.len() - 1]);
        segments.push(thin);
    }
    segments
}

/// A straight piece of a line, from one point to another.
type Segment = ((f64, f64), (f64, f64));

/// The part of the segment a–b inside the box \[x0, x1\] × \[y0, y1\] (Liang–Barsky), if any.
fn clip_segment(
    a: (f64, f64),
    b: (f64, f64),
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
) -> Option<Segment> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for (p, q) in [
        (-dx, a.0 - x0),
        (dx, x1 - a.0),
        (-dy, a.1 - y0),
        (dy, y1 - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    (t0 <= t1).then_some((
        (a.0 + t0 * dx, a.1 + t0 * dy),
        (a.0 + t1 * dx, a.1 + t1 * dy),
    ))
}

/// Tick labels without redundant digits: the precision follows the axis span (ticks are at
/// most span/20 apart in plotters' choice), trailing zeros are dropped and −0 reads 0.
fn tick_formatter(lo: f64, hi: f64) -> impl Fn(&f64) -> String {
    let span = (hi - lo).abs();
    let big = lo.abs().max(hi.abs());
    let scientific = big >= 1e6 || (big > 0.0 && big < 1e-3);
    let decimals = if span > 0.0 {
        (-(span / 100.0).log10()).ceil().clamp(0.0, 12.0) as usize
    } else {
        3
    };
    move |v: &f64| {
        let text = if scientific {
            let s = format!("{v:.3e}");
            match s.split_once('e') {
                Some((m, e)) => {
                    let m = if m.contains('.') {
                        m.trim_end_matches('0').trim_end_matches('.')
                    } else {
                        m
                    };
                    format!("{m}e{e}")
                }
                None => s,
            }
        } else {
            let s = format!("{v:.decimals$}");
            if s.contains('.') {
                s.trim_end_matches('0').trim_end_matches('.').to_string()
            } else {
                s
            }
        };
        if text == "-0" || text.starts_with("-0e") {
            text[1..].to_string()
        } else {
            text
        }
    }
}

const LEGEND_ROW: u32 = 20;

/// Lays legend entries out in rows of at most `width` pixels: (entry, x offset, row).
fn legend_layout(labels: &[(usize, u32)], width: u32) -> Vec<(usize, u32, u32)> {
    let (mut x, mut row) = (0u32, 0u32);
    let mut out = Vec::new();
    for &(k, text_w) in labels {
        let w = 34 + text_w + 18;
        if x > 0 && x + w > width {
            x = 0;
            row += 1;
        }
        out.push((k, x, row));
        x += w;
    }
    out
}

fn plot_err<E: std::fmt::Display>(e: E) -> anyhow::Error {
    anyhow!("plot: {e}")
}

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    panel: &Panel,
) -> Result<PanelReport>
where
    DB::ErrorType: 'static,
{
    let data_only = panel.series.iter().any(|s| s.role == Role::Data);
    let axis_points = || {
        panel
            .series
            .iter()
            .filter(move |s| !data_only || s.role == Role::Data)
            .flat_map(|s| s.points.iter())
    };
    let ranges = range_of(axis_points().map(|p| p.0))
        .and_then(|x| range_of(axis_points().map(|p| p.1)).map(|y| (x, y)));
    let mut report = PanelReport {
        title: panel.title.clone(),
        x_label: panel.x_label.clone(),
        y_label: panel.y_label.clone(),
        x_range: [0.0, 1.0],
        y_range: [0.0, 1.0],
        series: Vec::new(),
        note: None,
        skipped: None,
    };
    let ((x0, x1), (y0, y1)) = match ranges {
        Ok(r) => r,
        Err(why) => {
            eprintln!("note: plot \"{}\" skipped: {why}", panel.title);
            area.draw(&Text::new(
                format!("{}: not plotted ({why})", panel.title),
                (20, 40),
                ("sans-serif", 16),
            ))
            .map_err(plot_err)?;
            report.skipped = Some(why);
            return Ok(report);
        }
    };
    report.x_range = [x0, x1];
    report.y_range = [y0, y1];
    let inside = |p: &(f64, f64)| p.0 >= x0 && p.0 <= x1 && p.1 >= y0 && p.1 <= y1;
    // The clipped pieces of each series: polylines and isolated points.
    let mut pieces: Vec<Vec<Segment>> = Vec::new();
    let mut markers: Vec<Vec<(f64, f64)>> = Vec::new();
    for s in &panel.series {
        let mut lines = Vec::new();
        let mut dots = Vec::new();
        for run in drawable_segments(&s.points) {
            if run.len() == 1 {
                if inside(&run[0]) {
                    dots.push(run[0]);
                }
                continue;
            }
            for w in run.windows(2) {
                if let Some(seg) = clip_segment(w[0], w[1], (x0, x1), (y0, y1)) {
                    lines.push(seg);
                }
            }
        }
        pieces.push(lines);
        markers.push(dots);
    }
    let visible: Vec<bool> = (0..panel.series.len())
        .map(|k| !pieces[k].is_empty() || !markers[k].is_empty())
        .collect();
    let hidden: Vec<&str> = panel
        .series
        .iter()
        .zip(&visible)
        .filter(|(_, v)| !**v)
        .map(|(s, _)| s.label.as_str())
        .collect();
    let with_legend = panel.series.len() > 1;
    if !hidden.is_empty() && with_legend {
        report.note = Some(format!(
            "not drawn (no point inside the axes): {}",
            hidden.join(", ")
        ));
    } else if visible.iter().all(|v| !v) {
        report.note = Some("no data to draw".to_string());
    }
    // Legend strip below the chart.
    let label_style: TextStyle = ("sans-serif", 14).into_font().into();
    let entries: Vec<(usize, u32)> = if with_legend {
        panel
            .series
            .iter()
            .enumerate()
            .filter(|(k, _)| visible[*k])
            .map(|(k, s)| {
                let w = area
                    .estimate_text_size(&s.label, &label_style)
                    .map_or(8 * s.label.len() as u32, |d| d.0);
                (k, w)
            })
            .collect()
    } else {
        Vec::new()
    };
    let (w, h) = area.dim_in_pixel();
    let layout = legend_layout(&entries, w.saturating_sub(100));
    let rows = layout.iter().map(|e| e.2 + 1).max().unwrap_or(0);
    let strip = if rows > 0 { rows * LEGEND_ROW + 6 } else { 0 };
    let (chart_area, legend_area) = area.split_vertically(h.saturating_sub(strip));
    let mut title_area = chart_area
        .titled(&panel.title, ("sans-serif", 20))
        .map_err(plot_err)?;
    if let Some(note) = &report.note {
        title_area = title_area
            .titled(
                note,
                ("sans-serif", 13)
                    .into_font()
                    .color(&RGBColor(120, 120, 120)),
            )
            .map_err(plot_err)?;
    }
    let mut chart = ChartBuilder::on(&title_area)
        .margin(10)
        .margin_right(20)
        .x_label_area_size(40)
        .y_label_area_size(80)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(plot_err)?;
    let (fx, fy) = (tick_formatter(x0, x1), tick_formatter(y0, y1));
    chart
        .configure_mesh()
        .x_desc(&panel.x_label)
        .y_desc(&panel.y_label)
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(plot_err)?;
    for (k, s) in panel.series.iter().enumerate() {
        let colour = COLOURS[k % COLOURS.len()];
        let style = if s.role == Role::Reference {
            colour.stroke_width(1)
        } else {
            colour.stroke_width(2)
        };
        // Each piece its own path: no joins, so no mitre spikes beyond the frame.
        chart
            .draw_series(
                pieces[k]
                    .iter()
                    .map(|&(a, b)| PathElement::new(vec![a, b], style)),
            )
            .map_err(plot_err)?;
        chart
            .draw_series(
                markers[k]
                    .iter()
                    .map(|&p| Circle::new(p, 3, colour.filled())),
            )
            .map_err(plot_err)?;
        let finite = s
            .points
            .iter()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .count();
        let n_inside = s.points.iter().filter(|p| inside(p)).count();
        report.series.push(SeriesReport {
            label: s.label.clone(),
            role: match s.role {
                Role::Data => "data",
                Role::Reference => "reference",
            },
            points: s.points.len(),
            finite_points: finite,
            points_inside: n_inside,
            points_outside: finite - n_inside,
            drawn_pieces: pieces[k].len() + markers[k].len(),
            legend: entries.iter().any(|e| e.0 == k),
            colour: [colour.0, colour.1, colour.2],
            width: if s.role == Role::Reference { 1 } else { 2 },
        });
    }
    for (k, dx, row) in layout {
        let colour = COLOURS[k % COLOURS.len()];
        let (x, y) = (90 + dx as i32, 4 + (row * LEGEND_ROW) as i32 + 9);
        legend_area
            .draw(&PathElement::new(
                vec![(x, y), (x + 28, y)],
                colour.stroke_width(if panel.series[k].role == Role::Reference {
                    1
                } else {
                    2
                }),
            ))
            .map_err(plot_err)?;
        legend_area
            .draw(&Text::new(
                panel.series[k].label.clone(),
                (x + 34, y - 8),
                label_style.clone(),
            ))
            .map_err(plot_err)?;
    }
    Ok(report)
}

/// The figure's drawing area below its heading (the scenario's name).
fn headed<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>) -> Result<DrawingArea<DB, Shift>>
where
    DB::ErrorType: 'static,
{
    let name = scenario();
    if name.is_empty() {
        return Ok(root.clone());
    }
    root.titled(
        &format!("scenario: {name}"),
        ("sans-serif", 15).into_font().color(&RGBColor(90, 90, 90)),
    )
    .map_err(plot_err)
}

fn file_name(path: &Path) -> String {
    path.file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned())
}

/// Panels stacked vertically in one figure.
pub fn panels(path: &Path, panels: &[Panel]) -> Result<()> {
    let height = 24 + 380 * panels.len().max(1) as u32;
    struct Draw<'a>(&'a [Panel]);
    impl Draw<'_> {
        fn on<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<Vec<PanelReport>>
        where
            DB::ErrorType: 'static,
        {
            let body = headed(root)?;
            let areas = body.split_evenly((self.0.len().max(1), 1));
            let mut reports = Vec::new();
            for (area, panel) in areas.iter().zip(self.0) {
                reports.push(draw_panel(area, panel)?);
            }
            Ok(reports)
        }
    }
    let d = Draw(panels);
    let reports = render_with(path, (960, height), |r| d.on(r), |r| d.on(r))?;
    publish(&FigureReport {
        file: file_name(path),
        scenario: scenario().to_string(),
        panels: reports,
        maps: Vec::new(),
    })
}

fn render_with<T>(
    path: &Path,
    size: (u32, u32),
    bitmap: impl Fn(&DrawingArea<BitMapBackend, Shift>) -> Result<T>,
    svg: impl Fn(&DrawingArea<SVGBackend, Shift>) -> Result<T>,
) -> Result<T> {
    register_font();
    let is_svg = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("svg"));
    let mut result = None;
    write_atomic(path, |tmp| {
        if is_svg {
            let root = SVGBackend::new(tmp, size).into_drawing_area();
            root.fill(&WHITE).map_err(plot_err)?;
            result = Some(svg(&root)?);
            root.present().map_err(plot_err)?;
        } else {
            let root = BitMapBackend::new(tmp, size).into_drawing_area();
            root.fill(&WHITE).map_err(plot_err)?;
            result = Some(bitmap(&root)?);
            root.present().map_err(plot_err)?;
        }
        Ok(())
    })?;
    result.ok_or_else(|| anyhow!("plot: nothing drawn"))
}

/// A scalar field on a uniform grid.
pub struct Field<'a> {
    pub nx: usize,
    pub ny: usize,
    /// Lower-left corner and cell size, in the plot's units.
    pub x0: f64,
    pub y0: f64,
    pub dx: f64,
    pub dy: f64,
    /// Values, x fastest.
    pub values: &'a [f64],
}

/// How a map colours its cells.
pub enum Scale<'a> {
    /// A continuous colour bar (viridis) labelled `label`; cells where `exterior` is true are
    /// drawn light grey, outside the bar's colours, and named `exterior_label` under the bar.
    Continuous {
        label: &'a str,
        exterior: Option<(&'a [bool], &'a str)>,
    },
    /// Categories: each value is an index into the list of (label, colour); a legend of the
    /// categories with their cell counts replaces the colour bar.
    Categorical(&'a [(&'a str, RGBColor)]),
}

/// A colour map of a grid field, drawn with equal scales in x and y.
pub struct Map<'a> {
    pub title: String,
    pub x_label: &'a str,
    pub y_label: &'a str,
    pub field: Field<'a>,
    pub scale: Scale<'a>,
}

/// The light grey of cells outside a continuous scale (the exterior of a contact).
pub const EXTERIOR: RGBColor = RGBColor(215, 215, 215);

/// A perceptually ordered colour map (viridis, piecewise linear through 5 anchors).
fn viridis(t: f64) -> RGBColor {
    const ANCHORS: [(f64, f64, f64); 5] = [
        (68.0, 1.0, 84.0),
        (59.0, 82.0, 139.0),
        (33.0, 145.0, 140.0),
        (94.0, 201.0, 98.0),
        (253.0, 231.0, 37.0),
    ];
    let t = t.clamp(0.0, 1.0) * 4.0;
    let i = (t.floor() as usize).min(3);
    let f = t - i as f64;
    let (a, b) = (ANCHORS[i], ANCHORS[i + 1]);
    let mix = |x: f64, y: f64| (x + f * (y - x)).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// Widens the shorter of the two ranges about its centre so that a plotting area of
/// `pixels` shows both at the same scale (pixels per unit).
fn equal_aspect(
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
    pixels: (u32, u32),
) -> ((f64, f64), (f64, f64)) {
    let (pw, ph) = (pixels.0.max(1) as f64, pixels.1.max(1) as f64);
    let scale = (pw / (x1 - x0)).min(ph / (y1 - y0));
    let (wx, wy) = (pw / scale, ph / scale);
    let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    (
        (cx - 0.5 * wx, cx + 0.5 * wx),
        (cy - 0.5 * wy, cy + 0.5 * wy),
    )
}

const MAP_MARGIN: u32 = 12;
const MAP_X_LABELS: u32 = 40;
const MAP_Y_LABELS: u32 = 70;

impl Map<'_> {
    fn on<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<MapReport>
    where
        DB::ErrorType: 'static,
    {
        let f = &self.field;
        let (ex0, ex1) = (f.x0, f.x0 + f.nx as f64 * f.dx);
        let (ey0, ey1) = (f.y0, f.y0 + f.ny as f64 * f.dy);
        let mut report = MapReport {
            title: self.title.clone(),
            grid: [f.nx, f.ny],
            extent_x: [ex0, ex1],
            extent_y: [ey0, ey1],
            x_range: [ex0, ex1],
            y_range: [ey0, ey1],
            pixels_per_unit: [0.0, 0.0],
            scale: "continuous",
            bar_range: None,
            categories: Vec::new(),
            exterior_cells: 0,
        };
        let body = headed(root)?;
        let (main, side) = body.split_horizontally(body.dim_in_pixel().0 - 190);
        let main = main
            .titled(&self.title, ("sans-serif", 20))
            .map_err(plot_err)?;
        let (mw, mh) = main.dim_in_pixel();
        let plot_px = (
            mw.saturating_sub(2 * MAP_MARGIN + MAP_Y_LABELS),
            mh.saturating_sub(2 * MAP_MARGIN + MAP_X_LABELS),
        );
        let ((x0, x1), (y0, y1)) = equal_aspect((ex0, ex1), (ey0, ey1), plot_px);
        report.x_range = [x0, x1];
        report.y_range = [y0, y1];
        // Colours of the cells, and the scale's description.
        let colours: Vec<RGBColor> = match &self.scale {
            Scale::Continuous { label, exterior } => {
                let is_ext = |k: usize| exterior.is_some_and(|(e, _)| e[k]);
                let finite = || {
                    f.values
                        .iter()
                        .enumerate()
                        .filter(|&(k, v)| v.is_finite() && !is_ext(k))
                        .map(|(_, v)| *v)
                };
                let vmax = finite().fold(f64::NEG_INFINITY, f64::max);
                let vmin = finite().fold(f64::INFINITY, f64::min);
                let (vmin, vmax) = if vmin.is_finite() {
                    (vmin.min(0.0), vmax.max(0.0))
                } else {
                    (0.0, 0.0)
                };
                let span = if vmax > vmin { vmax - vmin } else { 1.0 };
                if !span.is_finite() || vmax.abs().max(vmin.abs()) > PLOT_MAX_MAGNITUDE {
                    eprintln!(
                        "note: plot \"{}\" skipped: values out of the plottable range",
                        self.title
                    );
                    root.draw(&Text::new(
                        format!("{}: not plotted (values out of range)", self.title),
                        (20, 60),
                        ("sans-serif", 16),
                    ))
                    .map_err(plot_err)?;
                    return Ok(report);
                }
                report.bar_range = Some([vmin, vmin + span]);
                let mut bar = ChartBuilder::on(&side)
                    .margin_top(60)
                    .margin_bottom(if exterior.is_some() { 110 } else { 60 })
                    .margin_right(20)
                    .y_label_area_size(90)
                    .caption(*label, ("sans-serif", 14))
                    .build_cartesian_2d(0.0..1.0, vmin..vmin + span)
                    .map_err(plot_err)?;
                let fy = tick_formatter(vmin, vmin + span);
                bar.configure_mesh()
                    .disable_mesh()
                    .disable_x_axis()
                    .y_label_formatter(&fy)
                    .label_style(("sans-serif", 12))
                    .draw()
                    .map_err(plot_err)?;
                let steps = 100;
                bar.draw_series((0..steps).map(|k| {
                    let a = vmin + span * k as f64 / steps as f64;
                    let b = vmin + span * (k + 1) as f64 / steps as f64;
                    Rectangle::new(
                        [(0.0, a), (1.0, b)],
                        viridis((k as f64 + 0.5) / steps as f64).filled(),
                    )
                }))
                .map_err(plot_err)?;
                if let Some((_, ext_label)) = exterior {
                    let (_, sh) = side.dim_in_pixel();
                    let y = sh as i32 - 80;
                    side.draw(&Rectangle::new([(20, y), (44, y + 16)], EXTERIOR.filled()))
                        .map_err(plot_err)?;
                    side.draw(&Rectangle::new([(20, y), (44, y + 16)], BLACK))
                        .map_err(plot_err)?;
                    side.draw(&Text::new(
                        ext_label.to_string(),
                        (50, y),
                        ("sans-serif", 13),
                    ))
                    .map_err(plot_err)?;
                }
                (0..f.values.len())
                    .map(|k| {
                        if is_ext(k) {
                            report.exterior_cells += 1;
                            EXTERIOR
                        } else {
                            viridis((f.values[k] - vmin) / span)
                        }
                    })
                    .collect()
            }
            Scale::Categorical(categories) => {
                report.scale = "categorical";
                let mut counts = vec![0usize; categories.len()];
                let colours = f
                    .values
                    .iter()
                    .map(|&v| {
                        let k = v as usize;
                        if v >= 0.0 && k < categories.len() {
                            counts[k] += 1;
                            categories[k].1
                        } else {
                            WHITE
                        }
                    })
                    .collect();
                for (k, ((label, colour), count)) in categories.iter().zip(&counts).enumerate() {
                    let y = 80 + 26 * k as i32;
                    side.draw(&Rectangle::new([(10, y), (34, y + 16)], colour.filled()))
                        .map_err(plot_err)?;
                    side.draw(&Rectangle::new([(10, y), (34, y + 16)], BLACK))
                        .map_err(plot_err)?;
                    side.draw(&Text::new(
                        format!("{label} ({count})"),
                        (40, y),
                        ("sans-serif", 13),
                    ))
                    .map_err(plot_err)?;
                    report.categories.push((label.to_string(), *count));
                }
                colours
            }
        };
        let mut chart = ChartBuilder::on(&main)
            .margin(MAP_MARGIN)
            .x_label_area_size(MAP_X_LABELS)
            .y_label_area_size(MAP_Y_LABELS)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(plot_err)?;
        let (fx, fy) = (tick_formatter(x0, x1), tick_formatter(y0, y1));
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(self.x_label)
            .y_desc(self.y_label)
            .x_label_formatter(&fx)
            .y_label_formatter(&fy)
            .label_style(("sans-serif", 14))
            .draw()
            .map_err(plot_err)?;
        chart
            .draw_series((0..f.ny).flat_map(|iy| {
                let colours = &colours;
                (0..f.nx).map(move |ix| {
                    let xa = f.x0 + ix as f64 * f.dx;
                    let ya = f.y0 + iy as f64 * f.dy;
                    Rectangle::new(
                        [(xa, ya), (xa + f.dx, ya + f.dy)],
                        colours[iy * f.nx + ix].filled(),
                    )
                })
            }))
            .map_err(plot_err)?;
        // The grid's outline, so the extent of the computed domain is visible.
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(ex0, ey0), (ex1, ey1)],
                RGBColor(60, 60, 60).stroke_width(1),
            )))
            .map_err(plot_err)?;
        let (px, py) = chart.plotting_area().get_pixel_range();
        report.pixels_per_unit = [
            (px.end - px.start) as f64 / (x1 - x0),
            (py.end - py.start) as f64 / (y1 - y0),
        ];
        Ok(report)
    }
}

/// Draws a map (see [`Map`]) into `path`.
pub fn map(path: &Path, map: &Map) -> Result<()> {
    let report = render_with(path, (960, 760), |r| map.on(r), |r| map.on(r))?;
    publish(&FigureReport {
        file: file_name(path),
        scenario: scenario().to_string(),
        panels: Vec::new(),
        maps: vec![report],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_are_sane_or_refused() {
        assert_eq!(range_of([0.0, 0.0].into_iter()), Ok((-1.0, 1.0)));
        assert_eq!(range_of([f64::NAN].into_iter()), Ok((0.0, 1.0)));
        let (lo, hi) = range_of([1.0, 2.0, f64::INFINITY].into_iter()).unwrap();
        assert!((lo - 0.96).abs() < 1e-12 && (hi - 2.04).abs() < 1e-12);
        assert!(range_of([1e-299, 2e-299].into_iter()).is_err());
        assert!(range_of([0.0, 3e290].into_iter()).is_err());
    }

    #[test]
    fn segments_break_at_non_finite_points_and_keep_peaks() {
        let s = drawable_segments(&[(0.0, 1.0), (1.0, f64::NAN), (2.0, 3.0), (3.0, 4.0)]);
        assert_eq!(s, vec![vec![(0.0, 1.0)], vec![(2.0, 3.0), (3.0, 4.0)]]);
        let long: Vec<(f64, f64)> = (0..100_000)
            .map(|i| (i as f64, if i == 54_321 { 9.0 } else { 0.0 }))
            .collect();
        let thin = drawable_segments(&long);
        assert!(thin[0].len() <= PLOT_MAX_POINTS + 1);
        assert!(thin[0].contains(&(54_321.0, 9.0)));
        assert!(thin[0].windows(2).all(|w| w[0].0 < w[1].0));
    }

    #[test]
    fn steps_join_adjacent_cells_and_break_at_gaps() {
        let s = Series::steps("s", &[(0.5, 1.0), (1.5, 2.0), (3.5, 3.0)], 1.0);
        let segs = drawable_segments(&s.points);
        assert_eq!(
            segs,
            vec![
                vec![(0.0, 1.0), (1.0, 1.0), (1.0, 2.0), (2.0, 2.0)],
                vec![(3.0, 3.0), (4.0, 3.0)]
            ]
        );
    }

    #[test]
    fn segments_are_clipped_to_the_box() {
        let b = ((0.0, 1.0), (0.0, 1.0));
        // Inside: unchanged.
        assert_eq!(
            clip_segment((0.2, 0.2), (0.8, 0.5), b.0, b.1),
            Some(((0.2, 0.2), (0.8, 0.5)))
        );
        // Through the box from below-left to above-right: cut at the frame.
        let (a, c) = clip_segment((-1.0, -1.0), (2.0, 2.0), b.0, b.1).unwrap();
        assert!((a.0 - 0.0).abs() < 1e-15 && (a.1 - 0.0).abs() < 1e-15);
        assert!((c.0 - 1.0).abs() < 1e-15 && (c.1 - 1.0).abs() < 1e-15);
        // A spike leaving through the top: ends on y = 1 at x = 0.5 + 0.5/10.
        let (_, c) = clip_segment((0.5, 0.0), (0.6, 10.0), b.0, b.1).unwrap();
        assert!((c.1 - 1.0).abs() < 1e-15 && (c.0 - 0.51).abs() < 1e-15);
        // Outside entirely.
        assert_eq!(clip_segment((2.0, 0.0), (3.0, 1.0), b.0, b.1), None);
        assert_eq!(clip_segment((-1.0, 2.0), (2.0, 2.0), b.0, b.1), None);
    }

    #[test]
    fn tick_labels_have_no_redundant_digits() {
        let f = tick_formatter(0.0, 10.0);
        assert_eq!(f(&2.0), "2");
        assert_eq!(f(&2.5), "2.5");
        let f = tick_formatter(-1.0, 1.0);
        assert_eq!(f(&-0.0), "0");
        assert_eq!(f(&-1e-17), "0");
        assert_eq!(f(&0.4), "0.4");
        assert_eq!(f(&-0.25), "-0.25");
        let f = tick_formatter(0.0, 3e9);
        assert_eq!(f(&2e9), "2e9");
        assert_eq!(f(&2.5e9), "2.5e9");
    }

    #[test]
    fn equal_aspect_widens_the_short_range() {
        // A 2:1 domain in a square area: y is widened to the x range.
        let ((x0, x1), (y0, y1)) = equal_aspect((0.0, 2.0), (0.0, 1.0), (400, 400));
        assert_eq!((x0, x1), (0.0, 2.0));
        assert!((y0 + 0.5).abs() < 1e-12 && (y1 - 1.5).abs() < 1e-12);
        // A tall domain in a wide area: x is widened.
        let ((x0, x1), (y0, y1)) = equal_aspect((0.0, 1.0), (0.0, 1.0), (600, 300));
        assert_eq!((y0, y1), (0.0, 1.0));
        assert!((x0 + 0.5).abs() < 1e-12 && (x1 - 1.5).abs() < 1e-12);
    }

    #[test]
    fn degenerate_panels_render_and_report_what_they_drew() {
        let dir = tempfile::tempdir().unwrap();
        let panel = |points: Vec<(f64, f64)>| Panel {
            title: "t".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            series: vec![
                Series::new("data series", points),
                Series::reference("reference line", vec![(-5.0, 0.5), (5.0, 0.5)]),
            ],
        };
        let path = dir.path().join("p.png");
        panels(
            &path,
            &[
                panel(vec![(0.0, 0.0), (1.0, 0.0)]),
                panel(vec![(0.0, 1e-299), (1.0, 3e290)]),
                panel(vec![(f64::NAN, f64::NAN)]),
                panel(vec![]),
            ],
        )
        .unwrap();
        assert!(std::fs::metadata(&path).unwrap().len() > 1000);
    }

    /// Blue pixels of the first series colour in the rows `rows` of an RGB buffer `w` wide.
    fn series_pixels(buf: &[u8], w: usize, rows: std::ops::Range<usize>) -> usize {
        let c = COLOURS[0];
        rows.flat_map(|y| (0..w).map(move |x| 3 * (y * w + x)))
            .filter(|&i| {
                let d = |a: u8, b: u8| (i32::from(a) - i32::from(b)).abs();
                d(buf[i], c.0) + d(buf[i + 1], c.1) + d(buf[i + 2], c.2) < 60
            })
            .count()
    }

    /// A dense zigzag (sharp turns at every point) stays inside the frame: nothing of the line
    /// reaches the title rows above the plotting area. Drawn the old way (one polyline of
    /// width 2, whose mitred joins overshoot at sharp turns), the same data does reach them,
    /// so the check can fail.
    #[test]
    fn sharp_turns_do_not_overshoot_the_frame() {
        register_font();
        let (w, h) = (600usize, 300usize);
        let zigzag: Vec<(f64, f64)> = (0..3000)
            .map(|i| (i as f64 * 1e-3, if i % 2 == 0 { 0.0 } else { 1.0 }))
            .collect();
        let panel = Panel {
            title: "zigzag".into(),
            x_label: "t [s]".into(),
            y_label: "y [m]".into(),
            series: vec![Series::new("zigzag", zigzag.clone())],
        };
        let mut buf = vec![255u8; 3 * w * h];
        {
            let root =
                BitMapBackend::with_buffer(&mut buf, (w as u32, h as u32)).into_drawing_area();
            draw_panel(&root, &panel).unwrap();
            root.present().unwrap();
        }
        // The title occupies the top rows; the plotting area starts below it.
        assert_eq!(series_pixels(&buf, w, 0..30), 0);
        let mut old = vec![255u8; 3 * w * h];
        {
            let root =
                BitMapBackend::with_buffer(&mut old, (w as u32, h as u32)).into_drawing_area();
            let area = root.titled("zigzag", ("sans-serif", 20)).unwrap();
            let mut chart = ChartBuilder::on(&area)
                .margin(10)
                .x_label_area_size(40)
                .y_label_area_size(80)
                .build_cartesian_2d(-0.12..3.12, -0.04..1.04)
                .unwrap();
            chart
                .draw_series(LineSeries::new(zigzag, COLOURS[0].stroke_width(2)))
                .unwrap();
            root.present().unwrap();
        }
        assert!(
            series_pixels(&old, w, 0..30) > 0,
            "the old drawing did not overshoot"
        );
    }

    #[test]
    fn a_map_keeps_equal_scales() {
        let dir = tempfile::tempdir().unwrap();
        let values = vec![1.0; 40 * 10];
        let m = Map {
            title: "m".into(),
            x_label: "x",
            y_label: "y",
            field: Field {
                nx: 40,
                ny: 10,
                x0: -2.0,
                y0: -0.25,
                dx: 0.1,
                dy: 0.05,
                values: &values,
            },
            scale: Scale::Continuous {
                label: "v",
                exterior: None,
            },
        };
        let report = render_with(
            &dir.path().join("m.png"),
            (960, 760),
            |r| m.on(r),
            |r| m.on(r),
        )
        .unwrap();
        let [sx, sy] = report.pixels_per_unit;
        // Integer pixel bounds: equal to within one pixel over the shorter extent.
        assert!((sx - sy).abs() / sx < 0.01, "{sx} vs {sy}");
        assert!(report.x_range[0] <= -2.0 && report.x_range[1] >= 2.0);
        assert!(report.y_range[0] <= -0.25 && report.y_range[1] >= 0.25);
    }
}
