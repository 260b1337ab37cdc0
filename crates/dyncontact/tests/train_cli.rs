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
