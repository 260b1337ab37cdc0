//! Plots (PNG or SVG, chosen by the file extension) with an embedded font, so no system
//! font library is needed.
//!
//! A figure is described by plain data ([`Panel`]s of [`Series`], or a [`Map`]); drawing it
//! also produces a [`FigureReport`](report::FigureReport) of what was drawn: the axes' ranges, for each series the
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
//! instead of a legend entry; panels of one figure with the same x label share one x range;
//! a panel of more series than line colours is drawn as several parts (each with the series
//! common to all parts, such as an envelope), so no two legend entries of a panel look alike;
//! maps keep equal scales in x and y; every figure is headed by the scenario's name
//! ([`set_scenario`]).
//!
//! Modules: `primitives` (colours, ranges, clipping, ticks, legend layout), `chart` (line
//! charts), `map` (colour maps), `report` (what a figure showed).

mod chart;
mod map;
mod primitives;
mod report;

use std::path::Path;
use std::sync::{Once, OnceLock};

use anyhow::{Result, anyhow};
use plotters::coord::Shift;
use plotters::prelude::*;
pub use plotters::style::RGBColor;

use crate::output::write_atomic;

pub use chart::{Panel, Series, panels};
pub use map::{EXTERIOR, Field, Map, Scale, map};

static FONT: Once = Once::new();
static SCENARIO: OnceLock<String> = OnceLock::new();

pub(crate) fn register_font() {
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

pub(crate) fn scenario() -> &'static str {
    SCENARIO.get().map_or("", String::as_str)
}

pub(crate) fn plot_err<E: std::fmt::Display>(e: E) -> anyhow::Error {
    anyhow!("plot: {e}")
}

/// The figure's drawing area below its heading (the scenario's name).
pub(crate) fn headed<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
) -> Result<DrawingArea<DB, Shift>>
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

pub(crate) fn file_name(path: &Path) -> String {
    path.file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned())
}

pub(crate) fn render_with<T>(
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
