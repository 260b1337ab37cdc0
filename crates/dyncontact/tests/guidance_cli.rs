//! Errors that say what to do next: a scenario of another kind given to `contact`, an unknown
//! method listing the valid ones, a misspelt key with the nearest valid key, `--integrator` on a
//! kind that does not take it.

mod support;

use support::{code, dyncontact, example, write};

fn stderr_of(args: &[&str]) -> (Option<i32>, String) {
    let o = dyncontact(args);
    (code(&o), String::from_utf8_lossy(&o.stderr).into_owned())
}

#[test]
fn a_vehicle_file_given_to_contact_names_its_kind_and_the_command() {
    let file = example("vehicle_bridge_default.toml");
    let (c, e) = stderr_of(&["contact", file.to_str().unwrap()]);
    assert_eq!(c, Some(2));
    assert!(
        e.contains("is a vehicle_bridge scenario") && e.contains("use `dyncontact run"),
        "{e}"
    );
}

#[test]
fn an_unknown_method_lists_the_valid_ones_and_the_nearest() {
    let file = example("ball_drop_steel.toml");
    let (c, e) = stderr_of(&[
        "run",
        file.to_str().unwrap(),
        "--integrator",
        "dopri",
        "--out",
        "/nonexistent-parent/x",
    ]);
    assert_eq!(c, Some(2));
    assert!(
        e.contains("unknown method (known: euler, rk4, dopri5"),
        "{e}"
    );
    assert!(e.contains("(did you mean `dopri5`?)"), "{e}");
    assert!(!e.contains("NaN"), "{e}");
    let (c, e) = stderr_of(&[
        "run",
        example("vehicle_bridge_biggs.toml").to_str().unwrap(),
        "--integrator",
        "newmark",
        "--out",
        "/nonexistent-parent/x",
    ]);
    assert_eq!(c, Some(2));
    assert!(
        e.contains("only ball_drop does") && e.contains("[integrator] method"),
        "{e}"
    );
}

#[test]
fn a_misspelt_key_gets_the_nearest_valid_key() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(example("vehicle_bridge_biggs.toml"))
        .unwrap()
        .replace("length = 25.0", "lenght = 25.0");
    let f = write(dir.path(), "s.toml", &text);
    let (c, e) = stderr_of(&["run", &f, "--out", dir.path().join("o").to_str().unwrap()]);
    assert_eq!(c, Some(2));
    assert!(
        e.contains("unknown field `lenght`") && e.contains("(did you mean `length`?)"),
        "{e}"
    );
    let text = std::fs::read_to_string(example("hertz_sphere.toml"))
        .unwrap()
        .replace("[load]", "[lod]");
    let f = write(dir.path(), "c.toml", &text);
    let (c, e) = stderr_of(&["contact", &f]);
    assert_eq!(c, Some(2));
    assert!(e.contains("(did you mean `load`?)"), "{e}");
}

/// `init KIND` writes a template that `run` accepts (the kind's example with a header);
/// an unknown kind lists the known ones; an existing file is not overwritten.
#[test]
fn init_writes_a_runnable_template_of_each_kind() {
    let dir = tempfile::tempdir().unwrap();
    for kind in [
        "ball_drop",
        "contact",
        "moving_load",
        "sweep",
        "vehicle_bridge",
    ] {
        let o = dyncontact(&["init", kind]);
        assert_eq!(code(&o), Some(0), "{kind}");
        let text = String::from_utf8(o.stdout).unwrap();
        assert!(text.contains(&format!("kind = \"{kind}\"")), "{kind}");
        let f = write(dir.path(), &format!("{kind}.toml"), &text);
        if kind == "ball_drop" || kind == "contact" {
            let out = dir.path().join(kind);
            let o = dyncontact(&["run", &f, "--out", out.to_str().unwrap()]);
            assert_eq!(
                code(&o),
                Some(0),
                "{kind}: {}",
                String::from_utf8_lossy(&o.stderr)
            );
        }
        let (c, e) = stderr_of(&["init", kind, "--out", &f]);
        assert_eq!(c, Some(2));
        assert!(e.contains("exists; not overwritten"), "{e}");
    }
    let (c, e) = stderr_of(&["init", "bridge"]);
    assert_eq!(c, Some(2));
    assert!(
        e.contains("known: ball_drop, contact, moving_load, sweep, vehicle_bridge"),
        "{e}"
    );
}

/// summary.json echoes its input (the file's name and the keys it set); CSV counts are
/// integers.
#[test]
fn summaries_echo_their_input_and_csv_counts_are_integers() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = dyncontact(&[
        "contact",
        example("hertz_sphere.toml").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code(&o), Some(0));
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["input"]["file"], "hertz_sphere.toml");
    assert_eq!(s["input"]["scenario"]["kind"], "contact");
    assert_eq!(s["input"]["scenario"]["load"]["force"], 1000.0);
    let out = dir.path().join("vb");
    let o = dyncontact(&[
        "run",
        example("vehicle_bridge_biggs.toml").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code(&o), Some(0));
    let csv = std::fs::read_to_string(out.join("timeseries.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = header.iter().position(|h| *h == "iterations").unwrap();
    for line in csv.lines().skip(1).take(50) {
        let v = line.split(',').nth(col).unwrap();
        assert!(v.parse::<u64>().is_ok(), "iterations written as {v}");
    }
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["input"]["scenario"]["vehicle"]["speed"], 27.78);
}

/// Every subcommand that writes files writes them into `./out` unless `--out` says otherwise
/// (`contact` and `modes` included).
#[test]
fn contact_and_modes_write_into_out_by_default() {
    for (args, file) in [
        (["contact", "hertz_sphere.toml"], "pressure.csv"),
        (["modes", "moving_load_fryba.toml"], "modes.json"),
    ] {
        let cwd = tempfile::tempdir().unwrap();
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_dyncontact"))
            .args([args[0], example(args[1]).to_str().unwrap()])
            .current_dir(cwd.path())
            .output()
            .unwrap();
        assert_eq!(code(&o), Some(0), "{args:?}");
        assert!(cwd.path().join("out").join(file).exists(), "{args:?}");
    }
}
