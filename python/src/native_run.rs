//! Bridges: `modes_text` (the modal table and mode shapes, `sim::modes`, as `dyncontact
//! modes`).

use numpy::{PyArray1, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};

use crate::SolverError;
use crate::guard::released;

/// Samples of the mode shapes along the span (as `dyncontact modes --out`).
const SHAPE_SAMPLES: usize = 401;

/// `modes_text(text) -> dict`: the modal table of a file's `[bridge]` section (`summary_json`,
/// the CLI's `modes.json`), and the mass-normalised mode shapes \[1/√kg\] at 401 points: `x`
/// (shape (401,)) and `shapes` (shape (401, modes)).
#[pyfunction]
pub fn modes_text<'py>(py: Python<'py>, text: &str) -> PyResult<Bound<'py, PyDict>> {
    let text = text.to_string();
    let (summary, rows) = released(py, move || {
        let bridge = sim::config::bridge::parse_bridge_file(&text)
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        let summary = sim::modes::summary(&bridge);
        let rows = sim::modes::shapes(&bridge, SHAPE_SAMPLES)
            .map_err(|e| SolverError::new_err(e.to_string()))?;
        Ok::<_, PyErr>((summary, rows))
    })??;
    let json =
        serde_json::to_string(&summary).map_err(|e| SolverError::new_err(format!("modes: {e}")))?;
    let n = summary.modes.len();
    let d = PyDict::new(py);
    d.set_item("summary_json", PyString::new(py, &json))?;
    let x: Vec<f64> = rows.iter().map(|r| r[0]).collect();
    let shapes: Vec<f64> = rows.iter().flat_map(|r| r[1..].iter().copied()).collect();
    d.set_item("x", PyArray1::from_vec(py, x))?;
    d.set_item(
        "shapes",
        PyArray1::from_vec(py, shapes).reshape([rows.len(), n])?,
    )?;
    Ok(d)
}
