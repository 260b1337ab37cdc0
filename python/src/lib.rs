//! `dyncontact._native`: the pyo3 extension module behind the Python package `dyncontact`
//! (python/dyncontact/__init__.py wraps it; python/dyncontact/_native.pyi documents it).
//!
//! Every entry point parses its input with the library's scenario code (`sim::config`), so a
//! dict, a TOML file and the CLI give the same case, and the same error messages naming the
//! key (raised as `ValueError`). Long computations run with the GIL released; a Rust panic is
//! caught and raised as `dyncontact.InternalError`, never unwinding into Python. The runs that
//! the library lets a caller stop (sweeps, creep curves, vehicle–bridge runs, ball drops) poll
//! Python's signal handlers every 50 ms, so Ctrl-C raises `KeyboardInterrupt`.

mod convert;
mod guard;
mod native_contact;
mod native_run;
mod native_sweep;

use pyo3::prelude::*;

pyo3::create_exception!(
    dyncontact,
    SolverError,
    pyo3::exceptions::PyRuntimeError,
    "A solver did not converge or failed; `iterations` and `residual` say how far it got."
);
pyo3::create_exception!(
    dyncontact,
    InternalError,
    pyo3::exceptions::PyRuntimeError,
    "A bug in dyncontact (a Rust panic caught at the boundary); please report it."
);

/// The extension module.
#[pymodule]
#[pyo3(name = "_native")]
fn native_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("SolverError", m.py().get_type::<SolverError>())?;
    m.add("InternalError", m.py().get_type::<InternalError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(convert::toml_text, m)?)?;
    m.add_function(wrap_pyfunction!(native_contact::solve_normal, m)?)?;
    m.add_function(wrap_pyfunction!(native_contact::contact_text, m)?)?;
    m.add_function(wrap_pyfunction!(native_contact::creep_curve_text, m)?)?;
    m.add_function(wrap_pyfunction!(native_run::modes_text, m)?)?;
    m.add_function(wrap_pyfunction!(native_run::run_text, m)?)?;
    m.add_function(wrap_pyfunction!(native_sweep::sweep_shard, m)?)?;
    m.add_function(wrap_pyfunction!(native_sweep::sweep_merge, m)?)?;
    m.add_function(wrap_pyfunction!(guard::panic_for_tests, m)?)?;
    Ok(())
}
