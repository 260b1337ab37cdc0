//! Exit codes, `--out` probing, run-owned output sets, concurrent runs into one directory,
//! and Ctrl-C (SIGINT) during a run — all with the real binary.

mod support;

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use support::{code, dyncontact, example, write};

/// A Hertz wheel crawling over a damped bridge; `speed` and `dt` set the length of the run.
fn crawl(speed: f64, dt: f64) -> String {
    format!(
        r#"
kind = "vehicle_bridge"
[bridge]
length = 25.0
EI = 8.323e9
mass_per_length = 2303.0
supports = "simply_supported"
modes = 10
damping_ratio = 0.05
[vehicle]
speed = {speed}
[[vehicle.wheels]]
position = 0.0
wheel_mass = 600.0
static_load = 94114.0
[contact]
model = "hertz"
[integrator]
method = "generalized_alpha"
rho_inf = 0.5
dt = {dt}
[output]
every = 1
"#
    )
}

fn stderr(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Every line has as many fields as the header, and the header appears once.
fn check_csv(path: &Path) -> usize {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines.next().expect("a header");
    let width = header.split(',').count();
    let mut rows = 0;
    for line in lines {
        let fields: Vec<&str> = line.split(',').collect();
        assert_eq!(
            fields.len(),
            width,
            "{}: row {rows}: {line}",
            path.display()
        );
        for f in fields {
            f.parse::<f64>()
                .unwrap_or_else(|_| panic!("{}: row {rows}: {f:?}", path.display()));
        }
        rows += 1;
    }
    assert!(
        text.ends_with('\n'),
        "{}: unterminated last row",
        path.display()
    );
    rows
}

/// 0 success, 1 run failed, 2 bad input — for every subcommand.
#[test]
fn exit_codes_are_documented_and_consistent() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let out = out.to_str().unwrap();
    let ok = dyncontact(&["modes", example("moving_load_fryba.toml").to_str().unwrap()]);
    assert_eq!(code(&ok), Some(0), "{}", stderr(&ok));
    let contact = example("hertz_sphere.toml");
    let contact = contact.to_str().unwrap();
    assert_eq!(code(&dyncontact(&["contact", contact, "--json"])), Some(0));
    // Bad input: a missing file, an invalid key, an unknown kind, a bad flag, a bad sweep.
    let bad_key = write(dir.path(), "bad.toml", &crawl(-2.0, 1e-3));
    let unknown = write(dir.path(), "unknown.toml", "kind = \"orbit\"\n");
    let bad_bridge = write(dir.path(), "bridge.toml", "[bridge]\nlength = -1.0\n");
    let cases: [&[&str]; 8] = [
        &["run", "/nonexistent/scenario.toml", "--out", out],
        &["run", &bad_key, "--out", out],
        &["run", &unknown, "--out", out],
        &["run", "--no-such-flag"],
        &["contact", "/nonexistent/case.toml"],
        &["modes", &bad_bridge],
        &["creep-curve", contact, "--out", out],
        &["creep-curve", contact, "--creepage-x", "0:1", "--out", out],
    ];
    for args in cases {
        let o = dyncontact(args);
        assert_eq!(code(&o), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains("error"), "{args:?}: {}", stderr(&o));
    }
    // A failed run: the normal solver stopped after 2 iterations (not converged).
    let case = std::fs::read_to_string(contact).unwrap() + "\n[solver]\nmax_iter = 2\n";
    let case = write(dir.path(), "short.toml", &case);
    let o = dyncontact(&["contact", &case, "--json"]);
    assert_eq!(code(&o), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("did not converge"), "{}", stderr(&o));
}

/// An unusable `--out` is reported before any work, naming the path, with exit code 2.
#[test]
fn unusable_out_fails_before_the_run() {
    let dir = tempfile::tempdir().unwrap();
    // A run of minutes if it started (0.05 m/s over 25 m: 5e6 steps, under the 1e7-row cap).
    let long = write(dir.path(), "long.toml", &crawl(0.05, 1e-4));
    let file = dir.path().join("a_file");
    std::fs::write(&file, "x").unwrap();
    let missing = dir.path().join("no/such/parent");
    for (out, says) in [
        (file.clone(), "not a directory"),
        (missing.clone(), "does not exist"),
    ] {
        let t = Instant::now();
        let o = dyncontact(&["run", &long, "--out", out.to_str().unwrap()]);
        assert_eq!(code(&o), Some(2), "{}", stderr(&o));
        let e = stderr(&o);
        assert!(e.contains(out.to_str().unwrap()) && e.contains(says), "{e}");
        assert!(
            t.elapsed() < Duration::from_secs(20),
            "took {:?}",
            t.elapsed()
        );
    }
    // An unwritable directory (not testable as root, who may write anywhere).
    let locked = dir.path().join("locked");
    std::fs::create_dir(&locked).unwrap();
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&locked, std::fs::Permissions::from_mode(0o555)).unwrap();
    if std::fs::write(locked.join("probe"), "x").is_err() {
        let o = dyncontact(&["run", &long, "--out", locked.to_str().unwrap()]);
        assert_eq!(code(&o), Some(2), "{}", stderr(&o));
        assert!(stderr(&o).contains("not writable"), "{}", stderr(&o));
    } else {
        eprintln!("running as root: the unwritable-directory case is not testable here");
    }
}

/// A second run replaces the first run's whole output set, and no private run directory is
/// left behind.
#[test]
fn a_run_replaces_the_previous_output_set() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    // Stale files of an earlier (interrupted) run of the same kind, and a foreign file.
    std::fs::write(out.join("timeseries.partial.csv"), "t\n1\n").unwrap();
    std::fs::write(out.join("pressure.png"), "old").unwrap();
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    let short = write(dir.path(), "short.toml", &crawl(25.0, 1e-3));
    let o = dyncontact(&["run", &short, "--out", out.to_str().unwrap()]);
    assert_eq!(code(&o), Some(0), "{}", stderr(&o));
    let mut names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    // The stale partial CSV is gone with its set; pressure.png is the new run's.
    assert_ne!(std::fs::read(out.join("pressure.png")).unwrap(), b"old");
    assert_eq!(
        names,
        [
            ".dyncontact.lock",
            "contact_force.png",
            "midspan.png",
            "notes.txt",
            "pressure.png",
            "summary.json",
            "timeseries.csv",
            "vehicle.png"
        ]
    );
    assert_eq!(check_csv(&out.join("timeseries.csv")), 1001);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["completed"], true);
    assert!((summary["time_reached"].as_f64().unwrap() - 1.0).abs() < 1e-9);
    // Hertz contact has a pressure; rigid contact has none (null, not 0).
    assert!(summary["contact"]["max_pressure"].as_f64().unwrap() > 1e8);
    let rigid = crawl(25.0, 1e-3).replace("model = \"hertz\"", "model = \"rigid\"");
    let rigid = write(dir.path(), "rigid.toml", &rigid);
    let o = dyncontact(&["run", &rigid, "--out", out.to_str().unwrap(), "--json"]);
    assert_eq!(code(&o), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(v["contact"]["max_pressure"].is_null(), "{v}");
}

/// Two runs writing into one `--out` at the same time: each final file is one run's whole
/// file (one header, well-formed rows), and the set is consistent (the summary's step count
/// matches the CSV). Repeated 4 times.
#[test]
fn concurrent_runs_into_one_directory_do_not_interleave() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    // Two different runs (500 and 1000 recorded steps) so a mix would show.
    let a = write(dir.path(), "a.toml", &crawl(25.0, 2e-3));
    let b = write(dir.path(), "b.toml", &crawl(25.0, 1e-3));
    for trial in 0..4 {
        let spawn = |file: &str| {
            Command::new(env!("CARGO_BIN_EXE_dyncontact"))
                .args(["run", file, "--out", out.to_str().unwrap(), "--json"])
                .stdout(Stdio::piped())
                .stderr(Stdio::piped())
                .spawn()
                .unwrap()
        };
        let (pa, pb) = (spawn(&a), spawn(&b));
        for p in [pa, pb] {
            let o = p.wait_with_output().unwrap();
            assert_eq!(code(&o), Some(0), "trial {trial}: {}", stderr(&o));
        }
        let rows = check_csv(&out.join("timeseries.csv"));
        let text = std::fs::read_to_string(out.join("timeseries.csv")).unwrap();
        assert_eq!(
            text.matches("t_s,").count(),
            1,
            "trial {trial}: two headers"
        );
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        let steps = summary["solver"]["steps"].as_u64().unwrap() as usize;
        assert_eq!(
            rows,
            steps + 1,
            "trial {trial}: CSV and summary of different runs"
        );
        let leftovers: Vec<_> = std::fs::read_dir(&out)
            .unwrap()
            .filter_map(|e| {
                let n = e.unwrap().file_name().to_string_lossy().into_owned();
                n.starts_with(".dyncontact-run-").then_some(n)
            })
            .collect();
        assert!(leftovers.is_empty(), "trial {trial}: {leftovers:?}");
    }
}

/// SIGINT during a long run: the run stops at its next step, writes a well-formed partial
/// time series (timeseries.partial.csv) and summary.json with `"completed": false` and the
/// time reached, and exits with 1.
#[test]
fn sigint_stops_the_run_and_marks_the_outputs_partial() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    // An old complete set must not survive beside the partial one.
    std::fs::write(out.join("timeseries.csv"), "t\n1\n").unwrap();
    // 500 s of simulated time at dt = 1e-4 (5e6 recorded rows, under the 1e7-row cap): many
    // minutes if it were not interrupted.
    let long = write(dir.path(), "long.toml", &crawl(0.05, 1e-4));
    let child = Command::new(env!("CARGO_BIN_EXE_dyncontact"))
        .args(["run", &long, "--out", out.to_str().unwrap(), "--json"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Wait until the run is stepping (its private directory holds a growing CSV).
    let t0 = Instant::now();
    loop {
        let growing = std::fs::read_dir(&out).unwrap().any(|e| {
            let p = e.unwrap().path();
            p.file_name()
                .unwrap()
                .to_string_lossy()
                .starts_with(".dyncontact-run-")
                && std::fs::metadata(p.join("timeseries.csv")).is_ok_and(|m| m.len() > 100_000)
        });
        if growing {
            break;
        }
        assert!(
            t0.elapsed() < Duration::from_secs(60),
            "the run did not start"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
    // SAFETY: sends SIGINT to the child we spawned.
    assert_eq!(unsafe { libc::kill(child.id() as i32, libc::SIGINT) }, 0);
    let t1 = Instant::now();
    let o = child.wait_with_output().unwrap();
    assert!(
        t1.elapsed() < Duration::from_secs(20),
        "slow stop: {:?}",
        t1.elapsed()
    );
    assert_eq!(code(&o), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("interrupted"), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["completed"], false);
    let reached = v["time_reached"].as_f64().unwrap();
    assert!(reached > 0.0 && reached < 2500.0, "{reached}");
    let file: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(file["completed"], false);
    assert!(
        !out.join("timeseries.csv").exists(),
        "a complete-looking CSV is left"
    );
    let rows = check_csv(&out.join("timeseries.partial.csv"));
    // Every step is recorded (every = 1): rows = steps taken + the initial state.
    let steps = v["solver"]["steps"].as_u64().unwrap() as usize;
    assert_eq!(rows, steps + 1);
    let last = std::fs::read_to_string(out.join("timeseries.partial.csv")).unwrap();
    let last_t: f64 = last
        .lines()
        .last()
        .unwrap()
        .split(',')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(
        (last_t - reached).abs() <= 1e-9 * reached.max(1.0),
        "{last_t} vs {reached}"
    );
}

/// Start `file` with `--json`, send SIGINT once the run is stepping (its private directory
/// has existed for `settle`), and check the interrupted run's outputs: exit code 1, a summary
/// (stdout and summary.json) with `"completed": false` and the time reached, the time series
/// only as `timeseries.partial.csv` (well-formed, ending at the time reached). Returns the
/// summary.
fn interrupt_run(
    file: &str,
    out: &Path,
    settle: Duration,
    time_column: usize,
) -> serde_json::Value {
    std::fs::create_dir_all(out).unwrap();
    std::fs::write(out.join("timeseries.csv"), "t\n1\n").unwrap();
    let child = Command::new(env!("CARGO_BIN_EXE_dyncontact"))
        .args(["run", file, "--out", out.to_str().unwrap(), "--json"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    while !std::fs::read_dir(out).unwrap().any(|e| {
        e.unwrap()
            .file_name()
            .to_string_lossy()
            .starts_with(".dyncontact-run-")
    }) {
        assert!(
            t0.elapsed() < Duration::from_secs(60),
            "the run did not start"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(settle);
    // SAFETY: sends SIGINT to the child we spawned.
    assert_eq!(unsafe { libc::kill(child.id() as i32, libc::SIGINT) }, 0);
    let t1 = Instant::now();
    let o = child.wait_with_output().unwrap();
    assert!(
        t1.elapsed() < Duration::from_secs(20),
        "slow stop: {:?}",
        t1.elapsed()
    );
    assert_eq!(code(&o), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("interrupted"), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["completed"], false, "{v}");
    assert!(v["stopped_by"].as_str().unwrap().contains("interrupt"));
    let file: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(file["completed"], false);
    assert_eq!(file["time_reached"], v["time_reached"]);
    assert!(
        !out.join("timeseries.csv").exists(),
        "a complete-looking CSV is left"
    );
    assert!(check_csv(&out.join("timeseries.partial.csv")) > 1);
    let reached = v["time_reached"].as_f64().unwrap();
    let text = std::fs::read_to_string(out.join("timeseries.partial.csv")).unwrap();
    let last_t: f64 = text
        .lines()
        .last()
        .unwrap()
        .split(',')
        .nth(time_column)
        .unwrap()
        .parse()
        .unwrap();
    assert!(
        reached > 0.0 && (last_t - reached).abs() <= 1e-9 * reached.max(1.0),
        "{last_t} vs {reached}"
    );
    v
}

/// SIGINT stops a ball drop (RK4, 1.1e7 fixed steps: minutes) at its next step.
#[test]
fn sigint_stops_a_ball_drop() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(example("ball_drop_steel.toml"))
        .unwrap()
        .replace("duration = 1.0", "duration = 10.0")
        .replace("method = \"radau5\"", "method = \"rk4\"\ndt = 1e-6")
        .replace("rtol = 1e-8\n", "")
        .replace("atol = 1e-12\n", "");
    let file = write(dir.path(), "long_drop.toml", &text);
    let v = interrupt_run(&file, &dir.path().join("out"), Duration::from_secs(1), 0);
    assert!(v["time_reached"].as_f64().unwrap() < 10.0);
    assert_eq!(v["final_time"], v["time_reached"]);
}

/// SIGINT stops a moving load (a force crawling at 3 mm/s: 8.3e7 exact modal steps) at its
/// next step.
#[test]
fn sigint_stops_a_moving_load() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(example("moving_load_fryba.toml"))
        .unwrap()
        .replace("speed = 27.78", "speed = 0.003")
        .replace("method = \"newmark\"", "method = \"exact\"");
    let file = write(dir.path(), "crawl.toml", &text);
    let v = interrupt_run(&file, &dir.path().join("out"), Duration::from_secs(1), 0);
    let reached = v["time_reached"].as_f64().unwrap();
    assert!(reached < 25.0 / 0.003, "{reached}");
}
