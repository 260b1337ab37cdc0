//! Python values as TOML: a dict with the structure of a scenario file becomes the text of that
//! file, which the library then parses exactly as it parses a file (same checks, same messages).

use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

/// The TOML value of a Python value; `key` names it in errors (`gap.radius`).
pub fn value(obj: &Bound<'_, PyAny>, key: &str) -> PyResult<toml::Value> {
    if obj.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(obj.extract()?));
    }
    if obj.is_instance_of::<PyInt>() {
        return obj.extract::<i64>().map(toml::Value::Integer).map_err(|_| {
            PyValueError::new_err(format!(
                "`{key}` = {obj}: an integer out of the 64-bit range"
            ))
        });
    }
    if obj.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(obj.extract()?));
    }
    if obj.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(obj.extract()?));
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        return table(d, key).map(toml::Value::Table);
    }
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let mut items = Vec::new();
        for (i, item) in obj.try_iter()?.enumerate() {
            items.push(value(&item?, &format!("{key}[{i}]"))?);
        }
        return Ok(toml::Value::Array(items));
    }
    if obj.hasattr("__fspath__")? {
        let path = obj.call_method0("__fspath__")?;
        return Ok(toml::Value::String(path.extract()?));
    }
    // numpy scalars and arrays: integers by __index__, floats by __float__, arrays by tolist().
    if obj.hasattr("tolist")? && obj.hasattr("dtype")? {
        return value(&obj.call_method0("tolist")?, key);
    }
    Err(PyTypeError::new_err(format!(
        "`{key}`: a {} cannot be a scenario value (use numbers, strings, booleans, lists and dicts)",
        obj.get_type().name()?
    )))
}

/// The TOML table of a dict; `key` is its path (empty at the top).
pub fn table(d: &Bound<'_, PyDict>, key: &str) -> PyResult<toml::Table> {
    let mut t = toml::Table::new();
    for (k, v) in d.iter() {
        let name: String = k.extract().map_err(|_| {
            PyTypeError::new_err(format!("`{key}`: keys must be strings, found {k}"))
        })?;
        let path = if key.is_empty() {
            name.clone()
        } else {
            format!("{key}.{name}")
        };
        if v.is_none() {
            continue; // None: the key is absent (its default applies).
        }
        t.insert(name, value(&v, &path)?);
    }
    Ok(t)
}

/// `toml_text(case: dict) -> str`: the TOML text of a scenario given as a dict (keys as in the
/// file; `None` values are left out).
#[pyfunction]
pub fn toml_text(case: &Bound<'_, PyDict>) -> PyResult<String> {
    let t = table(case, "")?;
    toml::to_string(&t).map_err(|e| PyValueError::new_err(format!("scenario dict: {e}")))
}
