//! `dyncontact bench contact` on the smallest grid: the table with its `solve/conv` column,
//! the small-grid table, and the tamaas comparison skipped with a clear line when the
//! interpreter is missing (the bench must not fail for lack of an optional library).
//! No timing is checked here: performance targets are read from the bench's output.

mod support;

use std::ffi::OsStr;
use support::dyncontact_env;

#[test]
fn contact_bench_runs_and_skips_tamaas_without_python() {
    let out = dyncontact_env(
        &["bench", "contact", "--max-n", "64"],
        &[("DYNCONTACT_PYTHON", OsStr::new("/nonexistent/python3"))],
    );
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(out.status.success(), "{text}");
    assert!(text.contains("solve/conv"), "{text}");
    assert!(text.contains("small grids"), "{text}");
    // Both loads at N = 64, with the Hertz errors of docs/verification.md's table.
    let rows: Vec<&str> = text
        .lines()
        .filter(|l| l.trim_start().starts_with("64 "))
        .collect();
    assert_eq!(rows.len(), 2, "{text}");
    assert!(rows[1].contains("-2.15e-3"), "{}", rows[1]);
    assert!(
        text.contains(
            "tamaas comparison at 64 × 64 skipped: no Python interpreter `/nonexistent/python3`"
        ),
        "{text}"
    );
}
