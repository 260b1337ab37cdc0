//! What a drawn figure showed ([`FigureReport`]), appended as one JSON line to the file named
//! by [`REPORT_ENV`] so that tests can check figures without looking at pixels.

use std::io::Write;
use std::path::Path;
use std::sync::Mutex;

use anyhow::{Result, anyhow};
use serde::Serialize;

static REPORT_LOCK: Mutex<()> = Mutex::new(());

/// The environment variable naming the file that figure reports are appended to.
pub const REPORT_ENV: &str = "DYNCONTACT_PLOT_REPORT";

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
pub(crate) fn publish(report: &FigureReport) -> Result<()> {
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
