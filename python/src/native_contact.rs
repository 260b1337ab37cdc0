//! Contact: `solve_normal` on a user-made gap, `contact_text` on a case (the library's
//! `sim::contact_case`, as `dyncontact contact`), `creep_curve_text` (`sim::creep_curve`).

use std::path::Path;
use std::sync::atomic::Ordering;
use std::time::Instant;

use halfspace::{ContactError, ElementState, NormalSolution, NormalSolver};
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use sim::config::contact::{BodySpec, LoadSpec, SolverSpec};
use sim::creep_curve::{CreepCurveError, CreepVariable};

use crate::SolverError;
use crate::convert;
use crate::guard::{interruptible, released};

fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// One body of `material` (`{"E": …, "nu": …}` or `{"rigid": True}`), as `[body1]`.
fn body(d: &Bound<'_, PyAny>, key: &str) -> PyResult<BodySpec> {
    let v = convert::value(d, key)?;
    v.try_into()
        .map_err(|e: toml::de::Error| value_error(format!("`{key}`: {}", e.message())))
}

/// `material`: `{"body1": {...}, "body2": {...}}` as the case file's sections, or one body's
/// keys for two identical bodies.
fn bodies(material: &Bound<'_, PyDict>) -> PyResult<(BodySpec, BodySpec)> {
    let b1 = material.get_item("body1")?;
    let b2 = material.get_item("body2")?;
    match (b1, b2) {
        (Some(b1), Some(b2)) => {
            if material.len() > 2 {
                return Err(value_error(
                    "`material`: with `body1` and `body2` give no other keys",
                ));
            }
            Ok((body(&b1, "material.body1")?, body(&b2, "material.body2")?))
        }
        (None, None) => Ok((
            body(material.as_any(), "material")?,
            body(material.as_any(), "material")?,
        )),
        _ => Err(value_error(
            "`material`: give both `body1` and `body2`, or one body's `E` and `nu` for identical bodies",
        )),
    }
}

fn f64_vec<'py>(py: Python<'py>, v: Vec<f64>) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_vec(py, v)
}

/// The arrays and scalars of a normal solution, as a dict (the Python wrapper builds its
/// result object from it).
fn normal_dict<'py>(
    py: Python<'py>,
    s: NormalSolution,
    solve_time_s: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let g = s.grid;
    let d = PyDict::new(py);
    let pressure = f64_vec(py, s.pressure).reshape([g.ny, g.nx])?;
    d.set_item("pressure", pressure)?;
    d.set_item("x", f64_vec(py, (0..g.nx).map(|i| g.x(i)).collect()))?;
    d.set_item("y", f64_vec(py, (0..g.ny).map(|i| g.y(i)).collect()))?;
    d.set_item("normal_force", s.normal_force)?;
    d.set_item("approach", s.approach)?;
    d.set_item("max_pressure", s.max_pressure)?;
    d.set_item("contact_area", s.contact_area)?;
    d.set_item("elements_in_contact", s.elements_in_contact)?;
    d.set_item("centre_of_pressure", s.centre_of_pressure)?;
    d.set_item("iterations", s.iterations)?;
    d.set_item("residual", s.residual)?;
    d.set_item("converged", s.converged)?;
    d.set_item("dfn_dapproach", s.dfn_dapproach)?;
    d.set_item("solve_time_s", solve_time_s)?;
    Ok(d)
}

/// `solve_normal(gap, dx, dy, material, force, approach, tol, max_iter) -> dict`: NormCG on a
/// user-made gap (shape (ny, nx), metres). The gap is read straight from a C-contiguous
/// float64 array (copied once into the solver's buffer, so the array may change after the
/// call returns but not during it); the solve runs with the GIL released. A solve that does
/// not converge returns its last iterate with `converged = False` (the wrapper raises
/// `SolverError`).
#[pyfunction]
#[pyo3(signature = (gap, dx, dy, material, force=None, approach=None, tol=None, max_iter=None))]
#[allow(clippy::too_many_arguments)]
pub fn solve_normal<'py>(
    py: Python<'py>,
    gap: PyReadonlyArray2<'py, f64>,
    dx: f64,
    dy: f64,
    material: &Bound<'py, PyDict>,
    force: Option<f64>,
    approach: Option<f64>,
    tol: Option<f64>,
    max_iter: Option<i64>,
) -> PyResult<Bound<'py, PyDict>> {
    let (ny, nx) = (gap.shape()[0], gap.shape()[1]);
    // Signed here so that a negative count gets the key's own message, not pyo3's overflow.
    let max_iter = match max_iter {
        Some(m) if m < 1 => {
            return Err(value_error(format!("`max_iter` = {m}: must be at least 1")));
        }
        Some(m) => Some(usize::try_from(m).unwrap_or(usize::MAX)),
        None => None,
    };
    let (b1, b2) = bodies(material)?;
    let load = LoadSpec { force, approach };
    let solver = SolverSpec { tol, max_iter };
    let h: Vec<f64> = match gap.as_slice() {
        Ok(s) => s.to_vec(),
        Err(_) => gap.as_array().iter().copied().collect(),
    };
    let input = sim::config::contact::user_gap(&b1, &b2, (nx, ny), (dx, dy), &h, &load, &solver)
        .map_err(|e| {
            value_error(
                e.to_string()
                    .replace("[load] ", "")
                    .replace("[solver] ", "")
                    .replace("`load.", "`")
                    .replace("`solver.", "`"),
            )
        })?;
    let (result, time) = released(py, move || {
        let start = Instant::now();
        let result = NormalSolver::new(input.grid, input.material)
            .and_then(|mut s| s.solve(&h, input.load, &input.options));
        (result, start.elapsed().as_secs_f64())
    })?;
    match result {
        Ok(s) => normal_dict(py, s, time),
        Err(ContactError::NotConverged { last, .. }) => normal_dict(py, *last, time),
        Err(e) => Err(value_error(e)),
    }
}

/// `contact_text(text, base) -> dict`: a contact case (TOML text; `base` resolves a gap
/// table's path) solved as `dyncontact contact` solves it: `summary_json` (the CLI's `--json`
/// object), the pressure and coordinates, and the exact tangential tractions when the case has
/// them. A non-converged normal solve is returned with `converged = False`.
#[pyfunction]
pub fn contact_text<'py>(py: Python<'py>, text: &str, base: &str) -> PyResult<Bound<'py, PyDict>> {
    let case = sim::config::contact::parse(text, Path::new(base)).map_err(value_error)?;
    let outcome = released(py, move || sim::contact_case::solve(&case))?
        .map_err(|e| SolverError::new_err(e.to_string()))?;
    let summary = serde_json::to_string(&outcome.summary)
        .map_err(|e| SolverError::new_err(format!("summary: {e}")))?;
    let d = normal_dict(py, outcome.solution, outcome.summary.solve_time_s)?;
    d.set_item("summary_json", PyString::new(py, &summary))?;
    if let Some(t) = outcome.tangential {
        let g = t.grid;
        d.set_item(
            "traction_x",
            f64_vec(py, t.traction_x).reshape([g.ny, g.nx])?,
        )?;
        d.set_item(
            "traction_y",
            f64_vec(py, t.traction_y).reshape([g.ny, g.nx])?,
        )?;
        let adhesion: Vec<bool> = t
            .state
            .iter()
            .map(|s| *s == ElementState::Adhesion)
            .collect();
        d.set_item(
            "adhesion",
            PyArray1::from_vec(py, adhesion).reshape([g.ny, g.nx])?,
        )?;
    }
    Ok(d)
}

/// `creep_curve_text(text, base, variable, values) -> str`: the creep curve of a contact case
/// with `[friction]` (`sim::creep_curve`), as the JSON of `dyncontact creep-curve`.
/// Interruptible between points.
#[pyfunction]
pub fn creep_curve_text(
    py: Python<'_>,
    text: &str,
    base: &str,
    variable: &str,
    values: Vec<f64>,
) -> PyResult<String> {
    let variable = match variable {
        "creepage_x" => CreepVariable::CreepageX,
        "creepage_y" => CreepVariable::CreepageY,
        "spin" => CreepVariable::Spin,
        other => {
            return Err(value_error(format!(
                "creepages: unknown variable `{other}` (creepage_x, creepage_y or spin)"
            )));
        }
    };
    if let Some(v) = values.iter().find(|v| !v.is_finite()) {
        return Err(value_error(format!(
            "`creepages` = {v}: every value must be finite"
        )));
    }
    if values.is_empty() || values.len() > 100_000 {
        return Err(value_error(format!(
            "`creepages`: {} values; give 1 … 100000",
            values.len()
        )));
    }
    let case = sim::config::contact::parse(text, Path::new(base)).map_err(value_error)?;
    sim::creep_curve::check(&case).map_err(value_error)?;
    let curve = interruptible(py, |stop| {
        sim::creep_curve::compute(&case, variable, &values, variable.key(), &|| {
            !stop.load(Ordering::Relaxed)
        })
    })?
    .map_err(|e| match e {
        CreepCurveError::NoMu | CreepCurveError::NotCreepages => value_error(e),
        other => SolverError::new_err(other.to_string()),
    })?;
    serde_json::to_string(&curve).map_err(|e| SolverError::new_err(format!("creep curve: {e}")))
}
