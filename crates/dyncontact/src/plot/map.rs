//! Colour maps of grid fields ([`Map`]), drawn with equal scales in x and y.

use std::path::Path;

use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::primitives::{PLOT_MAX_MAGNITUDE, tick_formatter};
use super::report::{FigureReport, MapReport, publish};
use super::{file_name, headed, plot_err, render_with, scenario};

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

impl<'a> Field<'a> {
    /// `values` on a contact grid, drawn in millimetres.
    pub fn on_grid_mm(g: &halfspace::Grid, values: &'a [f64]) -> Self {
        Self {
            nx: g.nx,
            ny: g.ny,
            x0: g.x0 * 1e3,
            y0: g.y0 * 1e3,
            dx: g.dx * 1e3,
            dy: g.dy * 1e3,
            values,
        }
    }
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
