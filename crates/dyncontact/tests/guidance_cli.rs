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

#[test]
fn a_load_whose_hertz_patch_exceeds_the_sphere_is_refused_with_its_keys() {
    // 1000 N on a 1 cm steel-like sphere with E = 2.5 Pa: a = (3 F R / (4 E*))^{1/3} =
    // 1.76 m, beyond the sphere (its gap R − √(R² − r²) ends at r = R). Before: "no contact:
    // the prescribed load gives no element in contact".
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(example("hertz_sphere.toml"))
        .unwrap()
        .replace("E = 210e9", "E = 2.5");
    let f = write(dir.path(), "c.toml", &text);
    let (c, e) = stderr_of(&[
        "contact",
        &f,
        "--out",
        dir.path().join("o").to_str().unwrap(),
    ]);
    assert_eq!(c, Some(2), "{e}");
    assert!(
        e.contains("a = 1.7609e0 m") && e.contains("`[gap] radius` = 0.01 m"),
        "{e}"
    );
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
    // creep_curve.json and modes.json echo their input too.
    for (args, file, key) in [
        (
            vec![
                "creep-curve",
                "tangential_rolling.toml",
                "--creepage-x",
                "0:0.001:2",
            ],
            "creep_curve.json",
            "friction",
        ),
        (
            vec!["modes", "moving_load_fryba.toml"],
            "modes.json",
            "bridge",
        ),
    ] {
        let out = dir.path().join(file);
        let path = example(args[1]);
        let mut argv = args.clone();
        argv[1] = path.to_str().unwrap();
        argv.extend(["--out", out.to_str().unwrap()]);
        assert_eq!(code(&dyncontact(&argv)), Some(0), "{argv:?}");
        let s: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join(file)).unwrap()).unwrap();
        assert_eq!(s["input"]["file"], args[1], "{file}");
        assert!(s["input"]["scenario"][key].is_object(), "{file}: {s}");
    }
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

/// `--help` lists the scenario kinds, points to `examples/` and the docs, says `contact` does
/// tangential contact too; `run --help` lists the methods per kind; no help text shows the
/// escaping of doc comments (`\[friction\]` in rustdoc reads `\[friction\]` in clap).
#[test]
fn help_names_kinds_examples_docs_and_reads_cleanly() {
    let help = String::from_utf8(dyncontact(&["--help"]).stdout).unwrap();
    for needle in [
        "ball_drop, contact, moving_load, sweep, vehicle_bridge",
        "examples/",
        "docs/",
        "tangential (shift, rolling)",
        "dyncontact init",
    ] {
        assert!(help.contains(needle), "--help lacks {needle:?}:\n{help}");
    }
    let run = String::from_utf8(dyncontact(&["run", "--help"]).stdout).unwrap();
    for needle in ["ball_drop", "vehicle_bridge newmark", "moving_load exact"] {
        assert!(run.contains(needle), "run --help lacks {needle:?}:\n{run}");
    }
    for sub in [
        "run",
        "contact",
        "modes",
        "creep-curve",
        "sweep",
        "sweep-merge",
        "init",
        "bench",
    ] {
        let o = dyncontact(&[sub, "--help"]);
        let text = String::from_utf8(o.stdout).unwrap();
        assert!(o.status.success() && !text.is_empty(), "{sub} --help");
        assert!(
            !text.contains('\\'),
            "{sub} --help shows an escape:\n{text}"
        );
    }
    assert!(!help.contains('\\'), "--help shows an escape:\n{help}");
}

/// The printed summaries say what they count: Radau5's rejected steps are "rejected", rigid
/// contact prints no pressure, a run without BEM no contact-solver iterations, and counts of
/// one are singular ("1 impact").
#[test]
fn printed_summaries_use_the_right_words() {
    let text = |file: &str| {
        let dir = tempfile::tempdir().unwrap();
        let o = dyncontact(&[
            "run",
            example(file).to_str().unwrap(),
            "--out",
            dir.path().join("o").to_str().unwrap(),
        ]);
        assert_eq!(code(&o), Some(0), "{file}");
        String::from_utf8(o.stdout).unwrap()
    };
    let radau = text("vehicle_bridge_radau5.toml");
    assert!(radau.contains(", 29 rejected steps"), "{radau}");
    assert!(
        !radau.contains("failed") && !radau.contains("contact-solver"),
        "{radau}"
    );
    let rigid = text("vehicle_bridge_biggs.toml");
    assert!(
        !rigid.contains("pressure") && !rigid.contains("contact-solver"),
        "{rigid}"
    );
    assert!(
        rigid.contains("0 loss-of-contact events, ")
            || rigid.contains("0 loss-of-contact events\n"),
        "{rigid}"
    );
    let hertz = text("vehicle_bridge_two_span_flat.toml");
    assert!(
        !hertz.contains("contact-solver") && hertz.contains("161 loss-of-contact events"),
        "{hertz}"
    );
    let bem = text("ball_drop_bem.toml");
    assert!(
        bem.contains(", 1 impact in 0.3 s; radau5: 85 steps (20 rejected)"),
        "{bem}"
    );
}
