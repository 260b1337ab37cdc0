//! Test support shared by the CLI tests (`mod support;` in each test file): run the binary,
//! write scenario files, find the examples.
// Each test crate uses a subset of these helpers.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Run the `dyncontact` binary built for these tests.
pub fn dyncontact(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_dyncontact"))
        .args(args)
        .output()
        .expect("binary runs")
}

/// Write `text` to `dir/name` and return the path as a string (for the command line).
pub fn write(dir: &Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.to_string_lossy().into_owned()
}

/// The path of `examples/NAME`.
pub fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name)
}

/// Run the binary, require success, and parse its standard output as JSON.
pub fn json_of(args: &[&str]) -> serde_json::Value {
    let out = dyncontact(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// The exit code of a finished process (`None` when a signal ended it).
pub fn code(out: &Output) -> Option<i32> {
    out.status.code()
}

/// The numeric value at a `/`-separated JSON pointer (`"contact/max_force"`).
pub fn num(v: &serde_json::Value, pointer: &str) -> f64 {
    v.pointer(&format!("/{pointer}"))
        .and_then(serde_json::Value::as_f64)
        .unwrap_or_else(|| panic!("missing numeric {pointer} in {v}"))
}
