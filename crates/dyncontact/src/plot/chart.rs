//! Line charts: [`Series`] in [`Panel`]s, stacked in one figure by [`panels`].

use std::path::Path;

use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::primitives::{
    COLOURS, LEGEND_ROW, Segment, clip_segment, drawable_segments, legend_layout, range_of,
    tick_formatter,
};
use super::report::{FigureReport, PanelReport, SeriesReport, publish};
use super::{file_name, headed, plot_err, render_with, scenario};

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
#[derive(Clone)]
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
    pub role: Role,
    /// Drawn in every part when a panel of more series than colours is split ([`panels`]):
    /// an envelope or a limit that each part is compared with. Reference curves always are.
    pub in_every_part: bool,
    /// Its colour's index in the palette; by default its position in the panel.
    colour_slot: Option<usize>,
}

impl Series {
    pub fn new(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            label: label.into(),
            points,
            role: Role::Data,
            in_every_part: false,
            colour_slot: None,
        }
    }

    /// The same series, drawn in every part of a split panel (see [`panels`]).
    pub fn in_every_part(self) -> Self {
        Series {
            in_every_part: true,
            ..self
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
#[derive(Clone)]
pub struct Panel {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
}

/// The axes' ranges of a panel, ((x0, x1), (y0, y1)), or why it cannot be plotted.
type Ranges = Result<((f64, f64), (f64, f64)), String>;

/// The axes' ranges of a panel: every finite point of its data series (of its reference
/// curves when it has no data) with a 4 % margin, or why it cannot be plotted.
fn panel_ranges(panel: &Panel) -> Ranges {
    let data_only = panel.series.iter().any(|s| s.role == Role::Data);
    let axis_points = || {
        panel
            .series
            .iter()
            .filter(move |s| !data_only || s.role == Role::Data)
            .flat_map(|s| s.points.iter())
    };
    range_of(axis_points().map(|p| p.0))
        .and_then(|x| range_of(axis_points().map(|p| p.1)).map(|y| (x, y)))
}

/// Draws one panel into `area` with the given axes' ranges (from [`panel_ranges`], possibly
/// widened to a range shared with other panels), or the reason it cannot be plotted.
fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    panel: &Panel,
    ranges: Ranges,
    part: Option<&str>,
) -> Result<PanelReport>
where
    DB::ErrorType: 'static,
{
    let mut report = PanelReport {
        title: part.map_or_else(|| panel.title.clone(), |p| format!("{} ({p})", panel.title)),
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
    if let Some(part) = part {
        title_area = title_area
            .titled(
                part,
                ("sans-serif", 15).into_font().color(&RGBColor(60, 60, 60)),
            )
            .map_err(plot_err)?;
    }
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
    let colour_of = |k: usize| COLOURS[panel.series[k].colour_slot.unwrap_or(k) % COLOURS.len()];
    for (k, s) in panel.series.iter().enumerate() {
        let colour = colour_of(k);
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
        let colour = colour_of(k);
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

/// A panel with more series than there are line colours, as several panels of one figure:
/// the series in every part ([`Series::in_every_part`], reference curves) in each, the others
/// in turn, so that no two legend entries of a panel look alike. The parts keep the whole
/// panel's axes (their curves compare across parts) and say which series they hold.
fn split_by_colours(panel: &Panel) -> Vec<Part> {
    if panel.series.len() <= COLOURS.len() {
        return vec![Part {
            panel: panel.clone(),
            ranges: panel_ranges(panel),
            part: None,
        }];
    }
    let whole = panel_ranges(panel);
    let (common, own): (Vec<&Series>, Vec<&Series>) = panel
        .series
        .iter()
        .partition(|s| s.in_every_part || s.role == Role::Reference);
    let room = COLOURS.len().saturating_sub(common.len()).max(1);
    let parts = own.len().div_ceil(room);
    own.chunks(room)
        .enumerate()
        .map(|(i, chunk)| {
            let first = &chunk[0].label;
            let last = &chunk[chunk.len() - 1].label;
            // The shared beginning of the labels is said once: "wheel 0 … 11".
            let same = first
                .chars()
                .zip(last.chars())
                .take_while(|(a, b)| a == b)
                .count();
            let prefix = first[..first.char_indices().nth(same).map_or(first.len(), |c| c.0)]
                .rfind(' ')
                .map_or(0, |i| i + 1);
            let part = Panel {
                title: panel.title.clone(),
                x_label: panel.x_label.clone(),
                y_label: panel.y_label.clone(),
                // The common series keep the last colours in every part, as in a panel of
                // twelve: the same envelope and limit line throughout.
                series: chunk
                    .iter()
                    .map(|s| (*s).clone())
                    .chain(common.iter().enumerate().map(|(j, s)| Series {
                        colour_slot: Some(COLOURS.len() - common.len().min(COLOURS.len()) + j),
                        ..(*s).clone()
                    }))
                    .collect(),
            };
            Part {
                panel: part,
                ranges: whole.clone(),
                part: Some(format!(
                    "part {} of {parts}: {first} … {}",
                    i + 1,
                    &last[prefix..]
                )),
            }
        })
        .collect()
}

/// One panel as drawn: its axes' ranges and, for a part of a split panel, which part.
struct Part {
    panel: Panel,
    ranges: Ranges,
    part: Option<String>,
}

/// Panels stacked vertically in one figure. Panels with the same x label share one x range
/// (one abscissa across the figure), and a panel of more series than line colours is drawn as
/// several parts ([`split_by_colours`]).
pub fn panels(path: &Path, panels: &[Panel]) -> Result<()> {
    let mut laid_out: Vec<Part> = panels.iter().flat_map(split_by_colours).collect();
    // One x range per x label: the union of the panels' ranges.
    for i in 0..laid_out.len() {
        let label = laid_out[i].panel.x_label.clone();
        let union = laid_out
            .iter()
            .filter(|p| p.panel.x_label == label)
            .filter_map(|p| p.ranges.as_ref().ok().map(|r| r.0))
            .reduce(|a, b| (a.0.min(b.0), a.1.max(b.1)));
        if let (Some(u), Ok(r)) = (union, &mut laid_out[i].ranges) {
            r.0 = u;
        }
    }
    let height = 24 + 380 * laid_out.len().max(1) as u32;
    struct Draw<'a>(&'a [Part]);
    impl Draw<'_> {
        fn on<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<Vec<PanelReport>>
        where
            DB::ErrorType: 'static,
        {
            let body = headed(root)?;
            let areas = body.split_evenly((self.0.len().max(1), 1));
            let mut reports = Vec::new();
            for (area, panel) in areas.iter().zip(self.0) {
                reports.push(draw_panel(
                    area,
                    &panel.panel,
                    panel.ranges.clone(),
                    panel.part.as_deref(),
                )?);
            }
            Ok(reports)
        }
    }
    let d = Draw(&laid_out);
    let reports = render_with(path, (960, height), |r| d.on(r), |r| d.on(r))?;
    publish(&FigureReport {
        file: file_name(path),
        scenario: scenario().to_string(),
        panels: reports,
        maps: Vec::new(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::primitives::drawable_segments;
    use crate::plot::register_font;

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
            draw_panel(&root, &panel, panel_ranges(&panel), None).unwrap();
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
}
