//! The plots' mechanical checks (`support::check_plot_report`) on the cases the examples do
//! not cover, and a check that the checker itself rejects each defect it is meant to find.
//! Every example's plots are checked in `examples_golden.rs`.

mod support;

use std::path::Path;

use support::{PLOT_REPORT_ENV, check_plot_report, dyncontact_env, example};

/// Run the binary with a plot report in `dir`; return the report's path (run must succeed).
fn run_reporting(args: &[&str], dir: &Path) -> std::path::PathBuf {
    let report = dir.join("plots.jsonl");
    let o = dyncontact_env(args, &[(PLOT_REPORT_ENV, report.as_os_str())]);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    report
}

/// Rigid contact has no pressure: no pressure.png (it used to be an empty 0–1 chart with a
/// legend of six snapshots), and every other figure passes the checks.
#[test]
fn rigid_contact_draws_no_empty_pressure_plot() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let report = run_reporting(
        &[
            "run",
            example("vehicle_bridge_biggs.toml").to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        dir.path(),
    );
    assert!(!out.join("pressure.png").exists());
    assert!(out.join("vehicle.png").exists());
    assert_eq!(check_plot_report(&report, &out, "biggs"), 3);
}

/// More series than line colours: a sweep of 13 trains (the ten HSLM-A, three trains given
/// by their axles) draws `acceleration.png` and `deflection.png` as two parts each, every part
/// with the envelope (and the limit line) and no two legend entries alike; a train of 16
/// wheelsets splits its per-wheel panels the same way. The checker requires distinct legend
/// entries and one x range per x label (so the parts share their axes).
#[test]
fn more_series_than_colours_are_split_into_parts() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(example("sweep_hslm.toml"))
        .unwrap()
        .replace(
            "[speeds]",
            "[[trains.train]]\nname = \"two axles\"\naxle_positions = [0.0, 3.0]\naxle_loads = [170e3, 170e3]\n\
             [[trains.train]]\nname = \"three axles\"\naxle_positions = [0.0, 3.0, 6.0]\naxle_loads = [150e3, 150e3, 150e3]\n\
             [[trains.train]]\nname = \"four axles\"\naxle_positions = [0.0, 2.5, 17.5, 20.0]\naxle_loads = [160e3, 160e3, 160e3, 160e3]\n\n[speeds]",
        );
    assert!(
        text.contains("four axles"),
        "the example has a [speeds] table"
    );
    let file = support::write(dir.path(), "sweep13.toml", &text);
    let out = dir.path().join("out");
    let report = run_reporting(
        &["sweep", &file, "--out", out.to_str().unwrap()],
        dir.path(),
    );
    check_plot_report(&report, &out, "13 trains");
    let figures: Vec<serde_json::Value> = std::fs::read_to_string(&report)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let acc = figures
        .iter()
        .find(|f| f["file"] == "acceleration.png")
        .unwrap();
    let parts = acc["panels"].as_array().unwrap();
    assert_eq!(parts.len(), 2, "{acc}");
    let mut trains = 0;
    for p in parts {
        let labels: Vec<&str> = p["series"]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| s["label"].as_str().unwrap())
            .collect();
        assert!(labels.len() <= 12, "{labels:?}");
        assert!(labels.contains(&"envelope"), "{labels:?}");
        assert!(labels.iter().any(|l| l.starts_with("limit")), "{labels:?}");
        trains += labels.len() - 2;
    }
    assert_eq!(trains, 13);
    let defl = figures
        .iter()
        .find(|f| f["file"] == "deflection.png")
        .unwrap();
    assert_eq!(
        defl["panels"].as_array().unwrap().len(),
        3,
        "two parts and φ'"
    );

    // 16 wheelsets: four Manchester cars, rigid contact, a short run.
    let text = std::fs::read_to_string(example("train_bridge.toml"))
        .unwrap()
        .replace("count = 2", "count = 4")
        .replace("model = \"hertz\"", "model = \"rigid\"")
        .replace("dt = 1e-4", "dt = 5e-4");
    let file = support::write(dir.path(), "train16.toml", &text);
    let out = dir.path().join("out16");
    let report = dir.path().join("plots16.jsonl");
    let o = dyncontact_env(
        &["run", &file, "--out", out.to_str().unwrap()],
        &[(PLOT_REPORT_ENV, report.as_os_str())],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    check_plot_report(&report, &out, "16 wheelsets");
    let text = std::fs::read_to_string(&report).unwrap();
    let force: serde_json::Value = text
        .lines()
        .map(|l| serde_json::from_str::<serde_json::Value>(l).unwrap())
        .find(|f| f["file"] == "contact_force.png")
        .unwrap();
    assert_eq!(
        force["panels"].as_array().unwrap().len(),
        2,
        "16 wheels + load line in two parts"
    );
}

/// `train.png`: the pictures of the train at several instants share one x range.
#[test]
fn train_pictures_share_one_abscissa() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let report = run_reporting(
        &[
            "run",
            example("train_bridge.toml").to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        dir.path(),
    );
    check_plot_report(&report, &out, "train");
    let text = std::fs::read_to_string(&report).unwrap();
    let train: serde_json::Value = text
        .lines()
        .map(|l| serde_json::from_str::<serde_json::Value>(l).unwrap())
        .find(|f| f["file"] == "train.png")
        .unwrap();
    let panels = train["panels"].as_array().unwrap();
    assert_eq!(panels.len(), 4);
    assert!(
        panels.iter().all(|p| p["x_range"] == panels[0]["x_range"]),
        "{train}"
    );
    // The track is drawn over the whole common range in every picture.
    for p in panels {
        let track = &p["series"][0];
        assert_eq!(track["label"], "track (deflection)");
        assert_eq!(track["points_outside"], 0);
    }
}

/// Creep curves through zero creepage, with the range written without `=` (it starts with a
/// minus sign), on the 2-D Carter case and on the 3-D rolling case: every point converges
/// (ξ = 0 is the traction-free solution, all loaded elements in adhesion), and the plots,
/// with the linear theory clipped to the axes, pass the checks.
#[test]
fn creep_curves_through_zero_plot_cleanly() {
    for (file, range, loaded) in [
        ("tangential_carter.toml", "-0.0004:0:5", 51),
        ("tangential_rolling.toml", "-0.004:0.004:5", 1396),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        let path = example(file);
        let args = [
            "creep-curve",
            path.to_str().unwrap(),
            "--creepage-x",
            range,
            "--out",
            out.to_str().unwrap(),
            "--json",
        ];
        let report = run_reporting(&args, dir.path());
        if file == "tangential_carter.toml" {
            // A cylinder gap: no FASTSIM or linear theory, and the title says why.
            let text = std::fs::read_to_string(&report).unwrap();
            assert!(
                text.contains("exact only: FASTSIM and linear theory need a Hertzian gap"),
                "{text}"
            );
        }
        let o = dyncontact_env(&args, &[]);
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        let points = v["points"].as_array().unwrap();
        assert_eq!(points.len(), 5, "{file}");
        let zero = points
            .iter()
            .find(|p| p["creepage_x"] == 0.0)
            .expect("a point at zero creepage");
        assert_eq!(zero["exact_force_x"], 0.0, "{file}");
        assert_eq!(zero["exact_slip_elements"], 0, "{file}");
        assert_eq!(zero["exact_adhesion_elements"], loaded, "{file}");
        assert!(
            points.iter().all(|p| p["exact_converged"] == true),
            "{file}"
        );
        assert_eq!(check_plot_report(&report, &out, file), 1);
    }
}

/// The checker finds each defect: a data point outside the axes, a legend entry without a
/// line, a series neither drawn nor named in the note, a one-letter legend label, an axis
/// label without unit, two legend entries drawn alike, a map with unequal scales, a
/// categorical legend that misses cells.
#[test]
fn the_plot_checker_rejects_each_defect() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path();
    std::fs::write(out.join("f.png"), b"png").unwrap();
    let series = |label: &str, outside: u64, drawn: u64, legend: bool| {
        // A colour per label, as the plots give one per series.
        let c: u64 = label.bytes().map(u64::from).sum();
        serde_json::json!({"label": label, "role": "data", "points": 10, "finite_points": 10,
            "points_inside": 10 - outside, "points_outside": outside, "drawn_pieces": drawn,
            "legend": legend, "colour": [c, 0, 0], "width": 2})
    };
    let panel = |series: Vec<serde_json::Value>, note: Option<&str>, y_label: &str| {
        serde_json::json!({"title": "t", "x_label": "t [s]", "y_label": y_label,
            "x_range": [0.0, 1.0], "y_range": [0.0, 1.0], "series": series, "note": note,
            "skipped": null})
    };
    let map = |ppu: [f64; 2], categories: serde_json::Value| {
        serde_json::json!({"title": "m", "grid": [2, 2], "extent_x": [0.0, 1.0],
            "extent_y": [0.0, 1.0], "x_range": [0.0, 1.0], "y_range": [0.0, 1.0],
            "pixels_per_unit": ppu, "scale": "categorical", "bar_range": null,
            "categories": categories, "exterior_cells": 0})
    };
    let figure = |panels: Vec<serde_json::Value>, maps: Vec<serde_json::Value>| serde_json::json!({"file": "f.png", "scenario": "s.toml", "panels": panels, "maps": maps});
    let good_panel = panel(
        vec![series("wheel 0", 0, 9, true), series("wheel 1", 0, 9, true)],
        None,
        "F [N]",
    );
    let good_map = map(
        [100.0, 100.0],
        serde_json::json!([["adhesion", 3], ["slip", 1]]),
    );
    let check = |fig: serde_json::Value| {
        let path = out.join("r.jsonl");
        std::fs::write(&path, format!("{fig}\n")).unwrap();
        std::panic::catch_unwind(|| check_plot_report(&path, out, "synthetic")).is_ok()
    };
    assert!(check(figure(
        vec![good_panel.clone()],
        vec![good_map.clone()]
    )));
    let defects = [
        panel(vec![series("wheel 0", 2, 9, false)], None, "F [N]"),
        panel(
            vec![series("wheel 0", 0, 9, true), series("wheel 1", 0, 0, true)],
            Some("not drawn: wheel 1"),
            "F [N]",
        ),
        panel(
            vec![
                series("wheel 0", 0, 9, true),
                series("wheel 1", 0, 0, false),
            ],
            None,
            "F [N]",
        ),
        panel(
            vec![series("w", 0, 9, true), series("wheel 1", 0, 9, true)],
            None,
            "F [N]",
        ),
        panel(vec![series("wheel 0", 0, 9, false)], None, "F"),
        // Two legend entries drawn alike.
        panel(
            vec![series("wheel 0", 0, 9, true), {
                let mut s = series("wheel 9", 0, 9, true);
                s["colour"] = series("wheel 0", 0, 9, true)["colour"].clone();
                s
            }],
            None,
            "F [N]",
        ),
    ];
    for (k, bad) in defects.into_iter().enumerate() {
        assert!(!check(figure(vec![bad], vec![])), "panel defect {k} passed");
    }
    // Two panels with one x label but different x ranges (no common abscissa).
    let mut shifted = good_panel.clone();
    shifted["x_range"] = serde_json::json!([0.0, 2.0]);
    assert!(!check(figure(vec![good_panel.clone(), shifted], vec![])));
    assert!(!check(figure(
        vec![],
        vec![map([100.0, 50.0], serde_json::json!([["adhesion", 4]]))]
    )));
    assert!(!check(figure(
        vec![],
        vec![map([100.0, 100.0], serde_json::json!([["adhesion", 3]]))]
    )));
}
