//! Plots (PNG or SVG, chosen by the file extension) with an embedded font, so no system
//! font library is needed.

use std::path::Path;
use std::sync::Once;

use anyhow::{Result, anyhow};
use plotters::coord::Shift;
use plotters::prelude::*;

use crate::output::write_atomic;

static FONT: Once = Once::new();

fn register_font() {
    FONT.call_once(|| {
        let _ = plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            dejavu::sans::regular(),
        );
    });
}

/// One line of a chart.
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
}

impl Series {
    pub fn new(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            label: label.into(),
            points,
        }
    }
}

/// One chart of a figure.
pub struct Panel {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
}

const COLOURS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
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

fn draw_panel<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, panel: &Panel) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let ranges = range_of(
        panel
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.0)),
    )
    .and_then(|x| {
        range_of(
            panel
                .series
                .iter()
                .flat_map(|s| s.points.iter().map(|p| p.1)),
        )
        .map(|y| (x, y))
    });
    let ((x0, x1), (y0, y1)) = match ranges {
        Ok(r) => r,
        Err(why) => {
            eprintln!("note: plot \"{}\" skipped: {why}", panel.title);
            area.draw(&Text::new(
                format!("{}: not plotted ({why})", panel.title),
                (20, 40),
                ("sans-serif", 16),
            ))
            .map_err(|e| anyhow!("plot: {e}"))?;
            return Ok(());
        }
    };
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(80)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|e| anyhow!("plot: {e}"))?;
    chart
        .configure_mesh()
        .x_desc(&panel.x_label)
        .y_desc(&panel.y_label)
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(|e| anyhow!("plot: {e}"))?;
    for (k, s) in panel.series.iter().enumerate() {
        let colour = COLOURS[k % COLOURS.len()];
        let segments = drawable_segments(&s.points);
        let mut first = true;
        for segment in segments.iter().chain(
            // An all-NaN series still gets its legend entry.
            segments.is_empty().then_some(&Vec::new()),
        ) {
            let drawn = chart
                .draw_series(LineSeries::new(
                    segment.iter().copied(),
                    colour.stroke_width(2),
                ))
                .map_err(|e| anyhow!("plot: {e}"))?;
            if first {
                drawn.label(s.label.clone()).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
                });
                first = false;
            }
        }
    }
    if panel.series.len() > 1 || panel.series.iter().any(|s| !s.label.is_empty()) {
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .label_font(("sans-serif", 14))
            .draw()
            .map_err(|e| anyhow!("plot: {e}"))?;
    }
    Ok(())
}

/// Panels stacked vertically in one figure.
pub fn panels(path: &Path, panels: &[Panel]) -> Result<()> {
    let height = 360 * panels.len().max(1) as u32;
    struct Draw<'a>(&'a [Panel]);
    impl Draw<'_> {
        fn on<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
        where
            DB::ErrorType: 'static,
        {
            let areas = root.split_evenly((self.0.len().max(1), 1));
            for (area, panel) in areas.iter().zip(self.0) {
                draw_panel(area, panel)?;
            }
            Ok(())
        }
    }
    let d = Draw(panels);
    render_with(path, (960, height), |r| d.on(r), |r| d.on(r))
}

fn render_with(
    path: &Path,
    size: (u32, u32),
    bitmap: impl Fn(&DrawingArea<BitMapBackend, Shift>) -> Result<()>,
    svg: impl Fn(&DrawingArea<SVGBackend, Shift>) -> Result<()>,
) -> Result<()> {
    register_font();
    let is_svg = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("svg"));
    write_atomic(path, |tmp| {
        if is_svg {
            let root = SVGBackend::new(tmp, size).into_drawing_area();
            root.fill(&WHITE).map_err(|e| anyhow!("plot: {e}"))?;
            svg(&root)?;
            root.present().map_err(|e| anyhow!("plot: {e}"))?;
        } else {
            let root = BitMapBackend::new(tmp, size).into_drawing_area();
            root.fill(&WHITE).map_err(|e| anyhow!("plot: {e}"))?;
            bitmap(&root)?;
            root.present().map_err(|e| anyhow!("plot: {e}"))?;
        }
        Ok(())
    })
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

/// A colour map of a grid field with a colour bar.
pub fn heatmap(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    bar_label: &str,
    field: &Field,
) -> Result<()> {
    struct Draw<'a, 'b> {
        title: &'a str,
        x_label: &'a str,
        y_label: &'a str,
        bar_label: &'a str,
        field: &'a Field<'b>,
    }
    impl Draw<'_, '_> {
        fn on<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
        where
            DB::ErrorType: 'static,
        {
            let f = self.field;
            let vmax = f
                .values
                .iter()
                .copied()
                .filter(|v| v.is_finite())
                .fold(0.0_f64, f64::max);
            let vmin = f
                .values
                .iter()
                .copied()
                .filter(|v| v.is_finite())
                .fold(vmax, f64::min)
                .min(0.0);
            let span = if vmax > vmin { vmax - vmin } else { 1.0 };
            if !span.is_finite() || vmax.abs().max(vmin.abs()) > PLOT_MAX_MAGNITUDE {
                eprintln!(
                    "note: plot \"{}\" skipped: values out of the plottable range",
                    self.title
                );
                root.draw(&Text::new(
                    format!("{}: not plotted (values out of range)", self.title),
                    (20, 40),
                    ("sans-serif", 16),
                ))
                .map_err(|e| anyhow!("plot: {e}"))?;
                return Ok(());
            }
            let (main, bar) = root.split_horizontally(root.dim_in_pixel().0 - 150);
            let (x0, x1) = (f.x0, f.x0 + f.nx as f64 * f.dx);
            let (y0, y1) = (f.y0, f.y0 + f.ny as f64 * f.dy);
            let mut chart = ChartBuilder::on(&main)
                .caption(self.title, ("sans-serif", 20))
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(70)
                .build_cartesian_2d(x0..x1, y0..y1)
                .map_err(|e| anyhow!("plot: {e}"))?;
            chart
                .configure_mesh()
                .disable_mesh()
                .x_desc(self.x_label)
                .y_desc(self.y_label)
                .label_style(("sans-serif", 14))
                .draw()
                .map_err(|e| anyhow!("plot: {e}"))?;
            chart
                .draw_series((0..f.ny).flat_map(|iy| {
                    (0..f.nx).map(move |ix| {
                        let v = f.values[iy * f.nx + ix];
                        let c = viridis((v - vmin) / span);
                        let xa = f.x0 + ix as f64 * f.dx;
                        let ya = f.y0 + iy as f64 * f.dy;
                        Rectangle::new([(xa, ya), (xa + f.dx, ya + f.dy)], c.filled())
                    })
                }))
                .map_err(|e| anyhow!("plot: {e}"))?;
            let mut bar_chart = ChartBuilder::on(&bar)
                .margin_top(44)
                .margin_bottom(52)
                .margin_right(10)
                .y_label_area_size(70)
                .caption(self.bar_label, ("sans-serif", 14))
                .build_cartesian_2d(0.0..1.0, vmin..vmin + span)
                .map_err(|e| anyhow!("plot: {e}"))?;
            bar_chart
                .configure_mesh()
                .disable_mesh()
                .disable_x_axis()
                .label_style(("sans-serif", 12))
                .draw()
                .map_err(|e| anyhow!("plot: {e}"))?;
            let steps = 100;
            bar_chart
                .draw_series((0..steps).map(|k| {
                    let a = vmin + span * k as f64 / steps as f64;
                    let b = vmin + span * (k + 1) as f64 / steps as f64;
                    Rectangle::new(
                        [(0.0, a), (1.0, b)],
                        viridis((k as f64 + 0.5) / steps as f64).filled(),
                    )
                }))
                .map_err(|e| anyhow!("plot: {e}"))?;
            Ok(())
        }
    }
    let d = Draw {
        title,
        x_label,
        y_label,
        bar_label,
        field,
    };
    render_with(path, (900, 760), |r| d.on(r), |r| d.on(r))
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
    fn degenerate_panels_render() {
        let dir = tempfile::tempdir().unwrap();
        let panel = |points: Vec<(f64, f64)>| Panel {
            title: "t".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            series: vec![Series::new("s", points)],
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
}
