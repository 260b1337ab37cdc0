//! `dyncontact run` with a `[train]`: the train's outputs (summary keys, the train picture).

mod support;

use support::{dyncontact, example};

#[test]
fn a_train_run_writes_its_summary_and_the_train_picture() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let path = example("train_bridge.toml");
    let o = dyncontact(&[
        "run",
        path.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["train"]["axles"], 8);
    assert_eq!(summary["vehicles"].as_array().unwrap().len(), 2);
    assert_eq!(summary["comfort"]["level"], "very good");
    assert!(std::fs::metadata(out.join("train.png")).unwrap().len() > 5000);
    // A run without a train writes no train picture.
    let plain = dir.path().join("plain");
    let o = dyncontact(&[
        "run",
        example("vehicle_bridge_biggs.toml").to_str().unwrap(),
        "--out",
        plain.to_str().unwrap(),
    ]);
    assert!(o.status.success());
    assert!(!plain.join("train.png").exists());
}

#[test]
fn a_long_train_run_records_a_bounded_time_series_with_exact_extrema() {
    // Eight Manchester cars (32 wheels) for 1.5 s at Δt = 1e-4 s: 15,001 rows of 309 values
    // (5 + 9 per wheel + 2 per car body) would be 4.6e6 values, above the default bound of 4e6, so without `[output] every` the
    // series records one step in 2; the summary's extrema are over every step, so they
    // equal those of the run that records every step.
    let scenario = |every: &str| {
        format!(
            "kind = \"vehicle_bridge\"\n[bridge]\nlength = 25.0\nEI = 8.323e9\nmass_per_length = 2303.0\nsupports = \"simply_supported\"\nmodes = 8\ndamping_ratio = 0.02\n[train]\nspeed = 83.3\nposition = -1.0\n[[train.vehicles]]\npreset = \"Manchester\"\ncount = 8\n[contact]\nmodel = \"hertz\"\n[integrator]\ndt = 1e-4\nduration = 1.5\n{every}"
        )
    };
    let dir = tempfile::tempdir().unwrap();
    let run = |name: &str, every: &str| {
        let file = dir.path().join(format!("{name}.toml"));
        std::fs::write(&file, scenario(every)).unwrap();
        let out = dir.path().join(name);
        let o = dyncontact(&[
            "run",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let mut summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        let summary = summary.as_object_mut().unwrap();
        for key in ["wall_time_s", "input"] {
            summary.remove(key);
        }
        let csv = std::fs::read_to_string(out.join("timeseries.csv")).unwrap();
        let rows = csv.lines().count() - 1;
        let width = csv.lines().next().unwrap().split(',').count();
        (
            summary.clone(),
            rows,
            width,
            String::from_utf8_lossy(&o.stdout).to_string(),
        )
    };
    let (default, rows, width, stdout) = run("default", "");
    let (every_step, all_rows, _, _) = run("every", "[output]\nevery = 1\n");
    assert_eq!(all_rows, 15_001);
    assert_eq!(width, 5 + 9 * 32 + 2 * 8);
    // Steps 0, 2, …, 15,000.
    assert_eq!(rows, 7_501, "{stdout}");
    assert!((rows * width) as f64 <= sim::config::vehicle_bridge::DEFAULT_SERIES_VALUES);
    assert!(stdout.contains("records one step in 2"), "{stdout}");
    assert_eq!(default, every_step);
}
