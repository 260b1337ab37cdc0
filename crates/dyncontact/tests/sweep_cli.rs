//! `dyncontact sweep` and `sweep-merge`: shards merge into the same outputs as one run, bad
//! input exits with 2 and names the key.

mod support;

use support::{code, dyncontact, write};

const SWEEP: &str = r#"kind = "sweep"
[bridge]
length = 15.0
EI = 7.5e9
mass_per_length = 10000.0
supports = "simply_supported"
modes = 3
damping_ratio = 0.02
[trains]
names = ["HSLM-A1", "HSLM-A7"]
[[trains.train]]
name = "two bogies"
axle_positions = [0.0, 2.5, 17.5, 20.0]
axle_loads = [150e3, 150e3, 150e3, 150e3]
[speeds]
from = 40.0
to = 80.0
step = 5.0
[output]
points = [7.5, 5.0]
"#;

fn summary_without_wall_time(dir: &std::path::Path) -> serde_json::Value {
    let text = std::fs::read_to_string(dir.join("summary.json")).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v.as_object_mut().unwrap().remove("wall_time_s");
    v
}

/// Runs `text` whole and as `shards` shards merged (in reverse order) in `dir`; checks that
/// the merged summary and CSV equal the whole run's; returns the whole run's directory and
/// the shards' directories.
fn whole_and_merged(
    dir: &std::path::Path,
    text: &str,
    shards: usize,
) -> (std::path::PathBuf, Vec<std::path::PathBuf>) {
    let file = write(dir, "sweep.toml", text);
    let whole = dir.join("whole");
    let o = dyncontact(&["sweep", &file, "--out", whole.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let mut shard_dirs = Vec::new();
    for k in 1..=shards {
        let d = dir.join(format!("shard{k}"));
        let shard = format!("{k}/{shards}");
        let o = dyncontact(&[
            "sweep",
            &file,
            "--out",
            d.to_str().unwrap(),
            "--shard",
            &shard,
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert!(d.join("shard.json").exists() && !d.join("summary.json").exists());
        shard_dirs.push(d);
    }
    let merged = dir.join("merged");
    let mut args = vec!["sweep-merge"];
    // Any order of the shards.
    for d in shard_dirs.iter().rev() {
        args.push(d.to_str().unwrap());
    }
    args.extend(["--out", merged.to_str().unwrap()]);
    let o = dyncontact(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(
        summary_without_wall_time(&whole),
        summary_without_wall_time(&merged)
    );
    assert_eq!(csv(&whole), csv(&merged), "sweep.csv must be bit-identical");
    (whole, shard_dirs)
}

fn csv(d: &std::path::Path) -> Vec<u8> {
    std::fs::read(d.join("sweep.csv")).unwrap()
}

#[test]
fn shards_merge_into_the_outputs_of_one_run() {
    let dir = tempfile::tempdir().unwrap();
    let (whole, shard_dirs) = whole_and_merged(dir.path(), SWEEP, 3);
    let s = summary_without_wall_time(&whole);
    assert_eq!(s["runs"], 27);
    assert_eq!(s["trains"].as_array().unwrap().len(), 3);
    assert_eq!(s["envelope"]["speeds"].as_array().unwrap().len(), 9);
    // One row per (train, speed, point) plus the header.
    assert_eq!(
        String::from_utf8(csv(&whole)).unwrap().lines().count(),
        1 + 27 * 2
    );
    for png in ["acceleration.png", "deflection.png", "governing.png"] {
        assert!(
            std::fs::metadata(whole.join(png)).unwrap().len() > 1000,
            "{png}"
        );
    }

    // A missing shard is refused.
    let o = dyncontact(&[
        "sweep-merge",
        shard_dirs[0].to_str().unwrap(),
        shard_dirs[2].to_str().unwrap(),
        "--out",
        dir.path().join("bad").to_str().unwrap(),
    ]);
    assert_eq!(code(&o), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("shard 2/3 is missing"));
}

#[test]
fn interaction_shards_merge_with_the_vehicles_peaks() {
    // The interaction model's passages carry the wheels' unloading, contact losses and the
    // car bodies' acceleration; shards store them exactly, so the merge equals the whole run.
    let text = r#"kind = "sweep"
[bridge]
length = 20.0
EI = 1.95e10
mass_per_length = 12000.0
supports = "simply_supported"
modes = 3
damping_ratio = 0.01
[trains]
names = ["AVE-S103-car", "double-deck-coach"]
model = "interaction"
[contact]
model = "hertz"
[speeds]
list = [40.0, 60.0]
"#;
    let dir = tempfile::tempdir().unwrap();
    let (whole, _) = whole_and_merged(dir.path(), text, 2);
    let s = summary_without_wall_time(&whole);
    for t in s["trains"].as_array().unwrap() {
        let ratio = t["max_unloading_ratio"].as_f64().unwrap();
        assert!(ratio > 0.0 && ratio < 1.0, "{t}");
        assert_eq!(t["loss_of_contact_events"], 0, "{t}");
        assert!(t["min_contact_force"].as_f64().unwrap() > 0.0, "{t}");
        assert!(t["max_body_acceleration"].as_f64().unwrap() > 0.0, "{t}");
        assert!(t["comfort_level"].is_string(), "{t}");
    }
    assert_eq!(
        s["envelope"]["max_unloading_ratio"]
            .as_array()
            .unwrap()
            .len(),
        2
    );
    let text = String::from_utf8(csv(&whole)).unwrap();
    let header = text.lines().next().unwrap();
    assert!(
        header.ends_with(
            "dynamic_factor,max_unloading_ratio,min_contact_force_n,loss_of_contact_events,max_body_acceleration_m_s2"
        ),
        "{header}"
    );
    // The moving-force model keeps its columns and keys.
    let moving = tempfile::tempdir().unwrap();
    let (whole, _) = whole_and_merged(moving.path(), SWEEP, 2);
    let header = String::from_utf8(csv(&whole)).unwrap();
    assert!(header.lines().next().unwrap().ends_with(",dynamic_factor"));
    let s = summary_without_wall_time(&whole);
    assert!(s["trains"][0].get("max_unloading_ratio").is_none());
    assert!(s["envelope"].get("max_unloading_ratio").is_none());
}

#[test]
fn bad_sweep_input_names_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (SWEEP.replace("\"HSLM-A7\"", "\"ICE9\""), "ICE9"),
        (SWEEP.replace("step = 5.0", "step = 0.0"), "`step`"),
        (
            SWEEP.replace("[trains]", "[trains]\nmodel = \"interaction\""),
            "interaction",
        ),
        (
            SWEEP.replace("damping_ratio = 0.02", "damping = \"eurocode\""),
            "needs `type`",
        ),
        (
            SWEEP.replace("points = [7.5, 5.0]", "points = [70.0]"),
            "points",
        ),
    ];
    for (text, key) in cases {
        let file = write(dir.path(), "bad.toml", &text);
        let o = dyncontact(&[
            "sweep",
            &file,
            "--out",
            dir.path().join("o").to_str().unwrap(),
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(code(&o), Some(2), "{err}");
        assert!(err.contains(key), "{key}: {err}");
    }
    let file = write(dir.path(), "ok.toml", SWEEP);
    let o = dyncontact(&["sweep", &file, "--shard", "4/3"]);
    assert_eq!(code(&o), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--shard 4/3"));
}

#[test]
fn help_lists_every_scenario_kind_and_the_sweep_commands() {
    let o = dyncontact(&["--help"]);
    let help = String::from_utf8_lossy(&o.stdout);
    for kind in sim::config::SCENARIO_KINDS {
        assert!(
            help.contains(kind),
            "--help does not list kind {kind}: {help}"
        );
    }
    for command in ["sweep", "sweep-merge", "examples/"] {
        assert!(help.contains(command), "{command}: {help}");
    }
}
