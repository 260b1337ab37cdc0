//! Test support shared by the CLI tests (`mod support;` in each test file): run the binary,
//! write scenario files, find the examples.
// Each test crate uses a subset of these helpers.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Run the `dyncontact` binary built for these tests, in a fresh working directory (every
/// subcommand writes into `./out` by default; a test that wants the files passes `--out`).
pub fn dyncontact(args: &[&str]) -> Output {
    dyncontact_env(args, &[])
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

/// Run the binary with extra environment variables.
pub fn dyncontact_env(args: &[&str], env: &[(&str, &std::ffi::OsStr)]) -> Output {
    let cwd = tempfile::tempdir().expect("a working directory");
    let mut c = Command::new(env!("CARGO_BIN_EXE_dyncontact"));
    c.args(args).current_dir(cwd.path());
    for (k, v) in env {
        c.env(k, v);
    }
    c.output().expect("binary runs")
}

/// The environment variable the binary appends its figure reports to (`plot::REPORT_ENV`).
pub const PLOT_REPORT_ENV: &str = "DYNCONTACT_PLOT_REPORT";

/// Checks the figure reports the binary wrote to `report` (one JSON object per line, see
/// `src/plot/report.rs`) for figures in `out`: every figure file exists and names its scenario;
/// every panel has axis labels with units and drawn data; every data point lies inside the
/// axes; panels of a figure with the same x label have the same x range (one abscissa);
/// every legend entry has a drawn line of its own colour and width; a panel of several series has a legend entry for
/// each drawn series, with a label longer than one letter, and names every
/// series it could not draw in its note; maps keep equal scales in x and y, contain their grid,
/// and have a colour bar or a categorical legend covering every cell. Returns the number of
/// figures checked; panics listing every defect.
pub fn check_plot_report(report: &Path, out: &Path, context: &str) -> usize {
    let text = std::fs::read_to_string(report)
        .unwrap_or_else(|e| panic!("{context}: no plot report {}: {e}", report.display()));
    let mut defects = Vec::new();
    let mut figures = 0;
    for line in text.lines() {
        let fig: serde_json::Value = serde_json::from_str(line).unwrap();
        figures += 1;
        let file = fig["file"].as_str().unwrap().to_string();
        let mut bad = |what: String| defects.push(format!("{file}: {what}"));
        if !out.join(&file).exists() {
            bad(format!("not in {}", out.display()));
        }
        if fig["scenario"].as_str().unwrap_or("").is_empty() {
            bad("no scenario name".into());
        }
        // One abscissa across a figure: panels with the same x label share one x range.
        let panels = fig["panels"].as_array().unwrap();
        for (i, p) in panels.iter().enumerate() {
            if let Some(q) = panels[..i].iter().find(|q| {
                q["x_label"] == p["x_label"]
                    && q["skipped"].is_null()
                    && p["skipped"].is_null()
                    && q["x_range"] != p["x_range"]
            }) {
                bad(format!(
                    "panels \"{}\" and \"{}\" share the x label {} but not the x range ({} and {})",
                    q["title"], p["title"], p["x_label"], q["x_range"], p["x_range"]
                ));
            }
        }
        for p in panels {
            let title = p["title"].as_str().unwrap();
            if let Some(why) = p["skipped"].as_str() {
                bad(format!("panel \"{title}\" skipped: {why}"));
                continue;
            }
            for axis in ["x_label", "y_label"] {
                let l = p[axis].as_str().unwrap();
                if !l.contains('[') {
                    bad(format!("panel \"{title}\": {axis} \"{l}\" has no unit"));
                }
            }
            let series = p["series"].as_array().unwrap();
            let note = p["note"].as_str().unwrap_or("");
            let (x, y) = (&p["x_range"], &p["y_range"]);
            if !(x[0].as_f64() < x[1].as_f64() && y[0].as_f64() < y[1].as_f64()) {
                bad(format!("panel \"{title}\": empty axes {x} × {y}"));
            }
            if !series.iter().any(|s| s["drawn_pieces"].as_u64() > Some(0)) {
                bad(format!("panel \"{title}\": nothing drawn"));
            }
            let styles: Vec<(String, String)> = series
                .iter()
                .filter(|s| s["legend"] == true)
                .map(|s| {
                    (
                        format!("{}/{}", s["colour"], s["width"]),
                        s["label"].to_string(),
                    )
                })
                .collect();
            for (i, (style, label)) in styles.iter().enumerate() {
                if let Some((_, other)) = styles[..i].iter().find(|(st, _)| st == style) {
                    bad(format!(
                        "panel \"{title}\": legend entries {other} and {label} look the same"
                    ));
                }
            }
            for s in series {
                let label = s["label"].as_str().unwrap();
                let drawn = s["drawn_pieces"].as_u64().unwrap();
                let legend = s["legend"].as_bool().unwrap();
                if s["role"] == "data" && s["points_outside"].as_u64() != Some(0) {
                    bad(format!(
                        "panel \"{title}\", \"{label}\": {} data points outside the axes",
                        s["points_outside"]
                    ));
                }
                if legend && drawn == 0 {
                    bad(format!(
                        "panel \"{title}\": legend entry \"{label}\" without a line"
                    ));
                }
                if drawn == 0 && !note.contains(label) {
                    bad(format!(
                        "panel \"{title}\": \"{label}\" not drawn and not noted"
                    ));
                }
                if series.len() > 1 && drawn > 0 && !legend {
                    bad(format!(
                        "panel \"{title}\": \"{label}\" drawn without a legend entry"
                    ));
                }
                if legend && label.chars().count() < 2 {
                    bad(format!(
                        "panel \"{title}\": legend label \"{label}\" says nothing"
                    ));
                }
            }
        }
        for m in fig["maps"].as_array().unwrap() {
            let title = m["title"].as_str().unwrap();
            let ppu = &m["pixels_per_unit"];
            let (sx, sy) = (ppu[0].as_f64().unwrap(), ppu[1].as_f64().unwrap());
            // Integer pixel bounds: 1 % covers a pixel of rounding on a 100-pixel side.
            if !(sx > 0.0 && (sx - sy).abs() <= 0.01 * sx) {
                bad(format!(
                    "map \"{title}\": unequal scales {sx} and {sy} px per unit"
                ));
            }
            let f = |v: &serde_json::Value, i: usize| v[i].as_f64().unwrap();
            let eps = 1e-9 * (f(&m["extent_x"], 1) - f(&m["extent_x"], 0)).abs();
            if f(&m["x_range"], 0) > f(&m["extent_x"], 0) + eps
                || f(&m["x_range"], 1) < f(&m["extent_x"], 1) - eps
                || f(&m["y_range"], 0) > f(&m["extent_y"], 0) + eps
                || f(&m["y_range"], 1) < f(&m["extent_y"], 1) - eps
            {
                bad(format!("map \"{title}\": the grid is not inside the axes"));
            }
            let cells = m["grid"][0].as_u64().unwrap() * m["grid"][1].as_u64().unwrap();
            match m["scale"].as_str().unwrap() {
                "categorical" => {
                    let counted: u64 = m["categories"]
                        .as_array()
                        .unwrap()
                        .iter()
                        .map(|c| c[1].as_u64().unwrap())
                        .sum();
                    if counted != cells {
                        bad(format!(
                            "map \"{title}\": legend counts {counted} of {cells} cells"
                        ));
                    }
                }
                _ => {
                    let b = &m["bar_range"];
                    if b.is_null() || f(b, 1) <= f(b, 0) {
                        bad(format!("map \"{title}\": no colour bar ({b})"));
                    }
                }
            }
        }
    }
    assert!(
        defects.is_empty(),
        "{context}: plot defects:\n{}",
        defects.join("\n")
    );
    figures
}
