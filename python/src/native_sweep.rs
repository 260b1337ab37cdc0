//! Sweeps: `sweep_shard` runs one shard K/N of a sweep (the library's `sim::sweep::run`, as
//! `dyncontact sweep --shard K/N`) and returns its `shard.json`; `sweep_merge` merges a
//! complete set of shards with the library's `sim::sweep::shard::merge` (as `dyncontact
//! sweep-merge`) into the report and the per-passage table. A local sweep is the one shard
//! 1/1 merged, a Dask sweep N shards run on the workers and merged: one code path.

use std::path::Path;
use std::sync::atomic::Ordering;
use std::time::Instant;

use numpy::PyArray1;
use pyo3::exceptions::{PyKeyboardInterrupt, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use sim::config::ScenarioConfig;
use sim::sweep::shard::{self, ShardFile};
use sim::sweep::{Shard, SweepError};

use crate::SolverError;
use crate::guard::{interruptible, released};

/// `sweep_shard(text, base, k, n) -> str`: the passages of shard `k` of `n` (1 ≤ k ≤ n) of
/// the sweep `text` (TOML, `kind = "sweep"`; `base` resolves train files), as the JSON of a
/// `shard.json` (floats exact). Interruptible (Ctrl-C) between passages.
#[pyfunction]
pub fn sweep_shard(py: Python<'_>, text: &str, base: &str, k: usize, n: usize) -> PyResult<String> {
    if n == 0 || k == 0 || k > n {
        return Err(PyValueError::new_err(format!(
            "shard {k}/{n}: expected 1 <= k <= n"
        )));
    }
    let base = Path::new(base);
    let config = match sim::config::load(text, base, &Default::default())
        .map_err(|e| PyValueError::new_err(e.to_string()))?
    {
        ScenarioConfig::Sweep(c) => *c,
        other => {
            return Err(PyValueError::new_err(format!(
                "`kind` = \"{}\": a sweep needs kind = \"sweep\"",
                other.kind()
            )));
        }
    };
    let shard = Shard { index: k, count: n };
    let start = Instant::now();
    let passages = interruptible(py, |stop| {
        sim::sweep::run(
            config.bridge.basis.as_ref(),
            &config.bridge.damping,
            &config.spec,
            shard,
            &|| !stop.load(Ordering::Relaxed),
        )
    })?;
    let passages = match passages {
        Ok(p) => p,
        Err(e @ SweepError::Interrupted { .. }) => {
            return Err(PyKeyboardInterrupt::new_err(e.to_string()));
        }
        Err(e) => return Err(SolverError::new_err(format!("sweep: {e}"))),
    };
    let file = ShardFile::new(text, base, shard, &passages, start.elapsed().as_secs_f64());
    serde_json::to_string(&file).map_err(|e| SolverError::new_err(format!("shard: {e}")))
}

/// `sweep_merge(shards) -> dict`: a complete set of shards (`shard.json` texts) merged:
/// `summary_json` (the CLI's `summary.json`) and the per-passage table of `sweep.csv` as
/// arrays (`train`, `speed_m_s`, `point_m`, `max_deflection_m`, `max_acceleration_m_s2`,
/// `max_static_deflection_m`, `dynamic_factor`).
#[pyfunction]
pub fn sweep_merge<'py>(py: Python<'py>, shards: Vec<String>) -> PyResult<Bound<'py, PyDict>> {
    let files = shards
        .iter()
        .enumerate()
        .map(|(i, t)| {
            serde_json::from_str::<ShardFile>(t)
                .map(|f| (format!("shard #{}", i + 1), f))
                .map_err(|e| PyValueError::new_err(format!("shard #{}: not a shard: {e}", i + 1)))
        })
        .collect::<PyResult<Vec<_>>>()?;
    let (report, table) = released(py, move || {
        // Every merge error is bad input: shards of other scenarios, an incomplete set, or a
        // scenario that no longer parses.
        let merged = shard::merge(&files).map_err(|e| PyValueError::new_err(e.to_string()))?;
        let report = shard::report(&merged.config, &merged.passages, merged.wall_time_s)
            .map_err(|e| SolverError::new_err(format!("sweep: {e}")))?;
        let table = sim::sweep::summary::passage_table(&merged.config.spec, &merged.passages);
        Ok::<_, PyErr>((report, table))
    })??;
    let json = serde_json::to_string(&report)
        .map_err(|e| SolverError::new_err(format!("sweep summary: {e}")))?;
    let d = PyDict::new(py);
    d.set_item("summary_json", PyString::new(py, &json))?;
    for (name, column) in table {
        d.set_item(name, PyArray1::from_vec(py, column))?;
    }
    Ok(d)
}
