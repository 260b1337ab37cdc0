//! Mutation fuzzing of the scenario reader (`sim::config`) over the shipped examples
//! (`examples/*.toml`, which include the built-in default scenario).
//!
//! Each case mutates an example: numeric values replaced by 0, −1, 1e-300, 1e300, NaN/inf,
//! huge integers or strings; keys deleted, duplicated or renamed; sections removed; strings
//! replaced; one to three mutations per case, from a fixed seed (deterministic).
//!
//! * `fuzz_scenario_reader` (CI, a few seconds): 3,000 cases, parse + validate only. Asserts
//!   no panic, every error message names a key of the file (or the section it lacks), and no
//!   single allocation above 1 GiB while reading (sizes are refused before allocating).
//! * `fuzz_scenario_runs` (`#[ignore]`, long): also RUNS every accepted scenario with a time
//!   limit and reports panics, runs over the limit, errors and non-finite outputs, ending with
//!   a `FIGURES:` line (the counts of issue #9). Run it with `DYNCONTACT_FUZZ_CASES=5000 cargo
//!   test --release -p sim --test fuzz_scenarios -- --ignored --nocapture`
//!   (`DYNCONTACT_FUZZ_LIMIT_S` sets the limit, default 30 s; `DYNCONTACT_FUZZ_MAX_WORK` the
//!   work budget, default [`FUZZ_MAX_WORK`]; `DYNCONTACT_FUZZ_SHOW=N` prints case N). A run past the limit is stopped at its next step
//!   through the simulations' observers and counted as a hang.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::ops::ControlFlow;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use sim::config::{self, ConfigError, LoadOptions, ScenarioConfig};

/// Records the largest single allocation of the current thread (forwarded to `System`).
struct Tracking;

thread_local! {
    static LARGEST: Cell<usize> = const { Cell::new(0) };
}

// SAFETY: forwards every call to `System`; only records the requested size.
unsafe impl GlobalAlloc for Tracking {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = LARGEST.try_with(|l| l.set(l.get().max(layout.size())));
        // SAFETY: the caller's contract is passed on unchanged.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: as above.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let _ = LARGEST.try_with(|l| l.set(l.get().max(new_size)));
        // SAFETY: as above.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOCATOR: Tracking = Tracking;

/// The largest single allocation allowed while reading a scenario \[bytes\].
const READ_ALLOCATION_LIMIT: usize = 1 << 30;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The shipped examples (the default scenario among them): (name, text).
fn seeds() -> Vec<(String, String)> {
    let mut out = Vec::new();
    let mut paths: Vec<PathBuf> = std::fs::read_dir(repo().join("examples"))
        .expect("examples/")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    paths.sort();
    for p in paths {
        let text = std::fs::read_to_string(&p).expect("readable example");
        out.push((p.file_name().unwrap().to_string_lossy().into_owned(), text));
    }
    assert!(out.len() >= 15, "examples missing: {}", out.len());
    out
}

/// Values substituted for a value.
const VALUES: &[&str] = &[
    "0",
    "0.0",
    "-1",
    "-1.0",
    "1e-300",
    "1e300",
    "-1e300",
    "nan",
    "inf",
    "-inf",
    "\"abc\"",
    "\"NaN\"",
    "9223372036854775807",
    "44000000",
    "1e9",
    "100000",
    "2e7",
    "true",
    "[]",
    "{}",
    "1e-7",
    "5e-8",
    "1e5",
];

/// `key = value` lines: (line index, key, value).
fn assignments(lines: &[String]) -> Vec<(usize, String, String)> {
    lines
        .iter()
        .enumerate()
        .filter_map(|(i, l)| {
            let t = l.trim_start();
            if t.starts_with('#') || t.starts_with('[') {
                return None;
            }
            let (k, v) = t.split_once('=')?;
            Some((i, k.trim().to_string(), v.trim().to_string()))
        })
        .collect()
}

/// One random mutation of `lines`.
fn mutate(lines: &mut Vec<String>, rng: &mut ChaCha8Rng) {
    let assigns = assignments(lines);
    let headers: Vec<usize> = (0..lines.len())
        .filter(|&i| lines[i].trim_start().starts_with('['))
        .collect();
    match rng.random_range(0..10) {
        0..=4 if !assigns.is_empty() => {
            let (i, k, _) = &assigns[rng.random_range(0..assigns.len())];
            let v = VALUES[rng.random_range(0..VALUES.len())];
            lines[*i] = format!("{k} = {v}");
        }
        5 if !assigns.is_empty() => {
            let (i, _, _) = assigns[rng.random_range(0..assigns.len())];
            lines.remove(i);
        }
        6 if !assigns.is_empty() => {
            let (i, k, _) = &assigns[rng.random_range(0..assigns.len())];
            let v = VALUES[rng.random_range(0..VALUES.len())];
            lines.insert(*i + 1, format!("{k} = {v}"));
        }
        7 if !assigns.is_empty() => {
            let (i, k, v) = &assigns[rng.random_range(0..assigns.len())];
            lines[*i] = format!("{k}x = {v}");
        }
        8 if !headers.is_empty() => {
            let h = rng.random_range(0..headers.len());
            let end = headers.get(h + 1).copied().unwrap_or(lines.len());
            lines.drain(headers[h]..end);
        }
        _ => {
            // Duplicate a whole section or an array-of-tables entry (many wheels, axles).
            if let Some(&start) = headers.get(rng.random_range(0..headers.len().max(1))) {
                let h = headers.iter().position(|&x| x == start).unwrap();
                let end = headers.get(h + 1).copied().unwrap_or(lines.len());
                let block: Vec<String> = lines[start..end].to_vec();
                let copies = if rng.random_bool(0.3) { 300 } else { 1 };
                for _ in 0..copies {
                    lines.splice(end..end, block.iter().cloned());
                }
            }
        }
    }
}

/// Key names and section names of a text (the words a message may name).
fn key_words(text: &str) -> Vec<String> {
    let mut words = Vec::new();
    for l in text.lines() {
        let t = l.split('#').next().unwrap_or("").trim();
        if t.starts_with('[') {
            let name = t.trim_matches(|c| c == '[' || c == ']');
            words.extend(name.split('.').map(str::to_string));
        } else if let Some((k, _)) = t.split_once('=') {
            words.push(k.trim().to_string());
        }
    }
    words.retain(|w| !w.is_empty());
    words
}

/// Does `message` name a key (of the mutated or the original file)?
fn names_a_key(message: &str, words: &[String]) -> bool {
    words.iter().any(|w| {
        message.contains(&format!("`{w}`"))
            || message.contains(&format!(".{w}"))
            || message.contains(&format!("{w}."))
            || message.contains(&format!("[{w}]"))
            || message.contains(&format!("{w} ="))
            || message.contains(&format!("`{w}")) // `vehicle.wheels[0]...`
    }) || message.contains("`kind`")
}

/// How reading one case ended.
enum Read {
    Accepted(Box<ScenarioConfig>),
    Contact(Box<config::contact::PreparedCase>),
    Refused(ConfigError),
}

/// Read a case; `max_work` is the work budget of [`LoadOptions::max_work`].
fn read(text: &str, base: &Path, max_work: Option<f64>) -> Read {
    let options = LoadOptions {
        max_work,
        ..LoadOptions::default()
    };
    let result = if text.contains("kind") {
        config::load(text, base, &options).map(|c| Read::Accepted(Box::new(c)))
    } else {
        config::contact::parse(text, base).map(|c| Read::Contact(Box::new(c)))
    };
    result.unwrap_or_else(Read::Refused)
}

/// Tallies of a campaign.
#[derive(Default, Debug)]
struct Tally {
    cases: usize,
    accepted: usize,
    refused: usize,
    panics: Vec<String>,
    without_key: Vec<String>,
    large_allocations: Vec<String>,
    run_panics: Vec<String>,
    run_over_limit: Vec<String>,
    run_errors: usize,
    run_error_samples: Vec<String>,
    /// Run failures (not input errors: the scenario was accepted) whose message names no key.
    run_errors_without_key: Vec<String>,
    run_non_finite: Vec<String>,
    runs_ok: usize,
    /// The ten longest runs: (wall time \[s\], label).
    slowest: Vec<(f64, String)>,
    /// Cases refused by the long mode's work budget (`LoadOptions::max_work`).
    over_budget: usize,
    /// Per kind, the largest wall time per estimated operation of a run over 1 s, and that
    /// run's estimate: (s per operation, operations).
    slowest_rate: std::collections::BTreeMap<&'static str, (f64, f64)>,
}

/// Generate `n` cases and read each; `run` also runs the accepted ones.
/// `run`: the time limit and the work budget of the long mode.
fn campaign(n: usize, run: Option<(Duration, f64)>) -> Tally {
    let seeds = seeds();
    let base = repo().join("examples");
    let mut rng = ChaCha8Rng::seed_from_u64(0x5eed_d1c0);
    let mut tally = Tally::default();
    let previous_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    for case in 0..n {
        let (name, text) = &seeds[rng.random_range(0..seeds.len())];
        let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
        for _ in 0..rng.random_range(1..=3) {
            mutate(&mut lines, &mut rng);
        }
        let mutated = lines.join("\n") + "\n";
        let label = format!("case {case} ({name})");
        if std::env::var("DYNCONTACT_FUZZ_SHOW").is_ok_and(|v| v == case.to_string()) {
            println!("{label}:\n{mutated}");
        }
        if run.is_some() && case % 100 == 0 {
            println!(
                "progress: {case} cases, {} accepted, {} runs ok, {} run errors, {} run panics, {} over the limit, {} non-finite; read: {} panics, {} without a key",
                tally.accepted,
                tally.runs_ok,
                tally.run_errors,
                tally.run_panics.len(),
                tally.run_over_limit.len(),
                tally.run_non_finite.len(),
                tally.panics.len(),
                tally.without_key.len()
            );
        }
        tally.cases += 1;
        LARGEST.with(|l| l.set(0));
        let budget = run.map(|(_, work)| work);
        let outcome = catch_unwind(AssertUnwindSafe(|| read(&mutated, &base, budget)));
        let largest = LARGEST.with(Cell::get);
        if largest > READ_ALLOCATION_LIMIT {
            tally
                .large_allocations
                .push(format!("{label}: {largest} bytes\n{mutated}"));
        }
        match outcome {
            Err(_) => tally.panics.push(format!("{label}\n{mutated}")),
            Ok(Read::Refused(e)) => {
                tally.refused += 1;
                if e.to_string().contains("--max-work") {
                    tally.over_budget += 1;
                }
                let message = e.to_string();
                let mut words = key_words(&mutated);
                words.extend(key_words(text));
                if !names_a_key(&message, &words) {
                    tally.without_key.push(format!("{label}: {message}"));
                }
            }
            Ok(read) => {
                tally.accepted += 1;
                if let Some((limit, work)) = run {
                    let estimate = match &read {
                        Read::Accepted(c) => {
                            config::cost::estimate(c).map(|w| (c.kind(), w.total()))
                        }
                        _ => None,
                    };
                    drop(read);
                    let mut words = key_words(&mutated);
                    words.extend(key_words(text));
                    let case = (label.as_str(), mutated.as_str(), words.as_slice());
                    let wall = run_case(&base, (limit, work), case, &mut tally);
                    if let Some((kind, total)) = estimate {
                        let rate = tally.slowest_rate.entry(kind).or_insert((0.0, 0.0));
                        if wall > 1.0 && wall / total > rate.0 {
                            *rate = (wall / total, total);
                        }
                    }
                }
            }
        }
    }
    std::panic::set_hook(previous_hook);
    tally
}

/// The outcome of a run: `Ok(all outputs finite)` or an error message.
type RunResult = Result<bool, String>;

/// The error a run returns when it passed the time limit (it stopped itself at a step).
const TIME_LIMIT: &str = "time limit";

fn simulate(read: Read, deadline: Instant) -> RunResult {
    let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
    let past = || Instant::now() > deadline;
    match read {
        Read::Refused(_) => Ok(true),
        Read::Contact(case) => normal_contact(&case),
        Read::Accepted(c) => match *c {
            ScenarioConfig::Contact(case) => normal_contact(&case),
            ScenarioConfig::BallDrop(b) => {
                let mut stop = |_: sim::ball_drop::Progress| {
                    if past() {
                        ControlFlow::Break(())
                    } else {
                        ControlFlow::Continue(())
                    }
                };
                let r = b
                    .scenario
                    .simulate_observed(false, &mut stop)
                    .map_err(|e| e.to_string())?;
                if !r.completed {
                    return Err(TIME_LIMIT.into());
                }
                Ok(r.energy_drift.is_finite()
                    && r.impacts
                        .iter()
                        .all(|i| i.peak_force.is_finite() && i.max_approach.is_finite()))
            }
            ScenarioConfig::MovingLoad(m) => {
                let mut stop = |_: beam::StepProgress| {
                    if past() {
                        ControlFlow::Break(())
                    } else {
                        ControlFlow::Continue(())
                    }
                };
                let r = beam::simulate_moving_loads_observed(
                    m.bridge.basis.as_ref(),
                    &m.bridge.damping,
                    &m.loads,
                    &m.settings,
                    &m.points,
                    &mut stop,
                )
                .map_err(|e| e.to_string())?;
                if !r.completed {
                    return Err(TIME_LIMIT.into());
                }
                Ok(finite(&r.deflection) && finite(&r.acceleration) && finite(&r.bending_moment))
            }
            ScenarioConfig::Sweep(c) => {
                let tick = || !past();
                match sim::sweep::run(
                    c.bridge.basis.as_ref(),
                    &c.bridge.damping,
                    &c.spec,
                    sim::sweep::Shard::ALL,
                    &tick,
                ) {
                    Ok(p) => Ok(p.iter().all(|p| {
                        finite(&p.peaks.deflection)
                            && finite(&p.peaks.acceleration)
                            && finite(&p.peaks.static_deflection)
                    })),
                    Err(sim::sweep::SweepError::Interrupted { .. }) => Err(TIME_LIMIT.into()),
                    Err(e) => Err(e.to_string()),
                }
            }
            ScenarioConfig::VehicleBridge(v) => {
                let v = *v;
                let mut s = sim::vehicle_bridge::Simulation::with_vehicles(v.scenario, v.vehicles)
                    .map_err(|e| e.to_string())?;
                if let Some(t) = v.traction {
                    s.set_traction(t).map_err(|e| e.to_string())?;
                }
                let end = s.end_time();
                while s.t() < end - 1e-9 * end.max(1.0) {
                    if past() {
                        return Err(TIME_LIMIT.into());
                    }
                    s.step().map_err(|e| e.to_string())?;
                }
                Ok(finite(s.state()) && s.wheels().iter().all(|w| w.contact.force.is_finite()))
            }
        },
    }
}

fn normal_contact(case: &config::contact::PreparedCase) -> RunResult {
    let mut solver =
        halfspace::NormalSolver::new(case.grid, case.material).map_err(|e| e.to_string())?;
    match solver.solve(&case.gap, case.load, &case.options) {
        Ok(s) => Ok(s.normal_force.is_finite() && s.pressure.iter().all(|p| p.is_finite())),
        Err(e) => Err(e.to_string()),
    }
}

/// Read (again, in the worker thread: the configs are not `Send`) and run one case. A run
/// past the limit stops itself at its next step (a run that does not, e.g. one stuck inside
/// one step, is abandoned after one more second and counted as over the limit too).
/// Returns the wall time \[s\].
/// `words`: the keys of the mutated file and of its seed (the words a message may name).
fn run_case(
    base: &Path,
    (limit, work): (Duration, f64),
    (label, text, words): (&str, &str, &[String]),
    tally: &mut Tally,
) -> f64 {
    let (tx, rx) = mpsc::channel();
    let start = Instant::now();
    let deadline = start + limit;
    let (base, owned) = (base.to_path_buf(), text.to_string());
    std::thread::spawn(move || {
        let r = catch_unwind(AssertUnwindSafe(|| {
            simulate(read(&owned, &base, Some(work)), deadline)
        }));
        let _ = tx.send(r);
    });
    let outcome = rx.recv_timeout(limit + Duration::from_secs(1));
    let wall = start.elapsed().as_secs_f64();
    tally.slowest.push((wall, label.to_string()));
    tally.slowest.sort_by(|a, b| b.0.total_cmp(&a.0));
    tally.slowest.truncate(10);
    match outcome {
        Err(_) => tally
            .run_over_limit
            .push(format!("{label} (stuck)\n{text}")),
        Ok(Err(_)) => tally.run_panics.push(format!("{label}\n{text}")),
        Ok(Ok(Err(e))) if e == TIME_LIMIT => tally.run_over_limit.push(format!("{label}\n{text}")),
        Ok(Ok(Err(e))) => {
            tally.run_errors += 1;
            if !names_a_key(&e, words) {
                tally.run_errors_without_key.push(format!("{label}: {e}"));
            }
            if tally.run_error_samples.len() < 10 {
                tally.run_error_samples.push(format!("{label}: {e}"));
            }
        }
        Ok(Ok(Ok(true))) => tally.runs_ok += 1,
        Ok(Ok(Ok(false))) => tally.run_non_finite.push(format!("{label}\n{text}")),
    }
    wall
}

fn report(t: &Tally) {
    println!(
        "{} cases: {} accepted, {} refused; {} panics, {} messages without a key, {} allocations > 1 GiB",
        t.cases,
        t.accepted,
        t.refused,
        t.panics.len(),
        t.without_key.len(),
        t.large_allocations.len()
    );
    for m in t.without_key.iter().take(20) {
        println!("  no key: {m}");
    }
    for m in t.panics.iter().take(5) {
        println!("  panic: {m}");
    }
    for m in t.large_allocations.iter().take(5) {
        println!("  allocation: {m}");
    }
}

/// CI: a few thousand cases, parse and validate only.
#[test]
fn fuzz_scenario_reader() {
    let start = Instant::now();
    let t = campaign(3000, None);
    report(&t);
    println!("{:.1} s", start.elapsed().as_secs_f64());
    assert!(t.refused > 1000 && t.accepted > 100, "{t:?}");
    assert!(
        t.panics.is_empty(),
        "panics: {:#?}",
        &t.panics[..t.panics.len().min(3)]
    );
    assert!(
        t.without_key.is_empty(),
        "messages without a key: {:#?}",
        &t.without_key[..t.without_key.len().min(10)]
    );
    assert!(t.large_allocations.is_empty(), "{:#?}", t.large_allocations);
}

/// The long mode's default work budget \[operations\] (`DYNCONTACT_FUZZ_MAX_WORK`): the
/// product's limit (`sim::config::cost::MAX_WORK`, a day of work) lets through runs of hours
/// that are sensible (small steps, long trains); the fuzz refuses those up front like a user
/// who passes `--max-work`, and checks that every run it accepts ends within the time limit
/// (a run that does not had a wrong cost estimate or spun).
const FUZZ_MAX_WORK: f64 = 5e9;

/// Long mode: read AND run (module documentation).
#[test]
#[ignore = "long: runs every accepted scenario (DYNCONTACT_FUZZ_CASES, DYNCONTACT_FUZZ_LIMIT_S)"]
fn fuzz_scenario_runs() {
    let n = std::env::var("DYNCONTACT_FUZZ_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(5000);
    let limit = std::env::var("DYNCONTACT_FUZZ_LIMIT_S")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(30.0);
    let work = std::env::var("DYNCONTACT_FUZZ_MAX_WORK")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(FUZZ_MAX_WORK);
    let start = Instant::now();
    let t = campaign(n, Some((Duration::from_secs_f64(limit), work)));
    report(&t);
    println!(
        "work budget {work:e} operations: {} cases refused by it",
        t.over_budget
    );
    for (kind, (rate, total)) in &t.slowest_rate {
        println!(
            "  {kind}: slowest {:.2e} s per 1e9 estimated operations (a run of {total:.2e})",
            rate * 1e9
        );
    }
    println!(
        "runs: {} ok, {} failed with an error, {} panics, {} over {limit} s, {} with non-finite outputs; {:.0} s",
        t.runs_ok,
        t.run_errors,
        t.run_panics.len(),
        t.run_over_limit.len(),
        t.run_non_finite.len(),
        start.elapsed().as_secs_f64()
    );
    for (wall, label) in &t.slowest {
        println!("  slow: {wall:.1} s {label}");
    }
    for m in &t.run_error_samples {
        println!("  run error: {m}");
    }
    for m in t
        .run_panics
        .iter()
        .chain(&t.run_over_limit)
        .chain(&t.run_non_finite)
        .take(10)
    {
        println!("---\n{m}");
    }
    for m in &t.run_errors_without_key {
        println!("  run error without a key: {m}");
    }
    // The figures of issue #9 (an allocation abort would have ended this process).
    println!(
        "FIGURES: {} inputs, {} run ({} refused by the work budget {work:e}); panics {}, aborts 0, hangs over {limit} s {}, messages without a key {} (and {} of the {} run failures), non-finite outputs {}",
        t.cases,
        t.accepted,
        t.over_budget,
        t.panics.len() + t.run_panics.len(),
        t.run_over_limit.len(),
        t.without_key.len(),
        t.run_errors_without_key.len(),
        t.run_errors,
        t.run_non_finite.len()
    );
    assert!(t.panics.is_empty() && t.without_key.is_empty());
    assert!(t.run_panics.is_empty(), "run panics");
    assert!(t.run_non_finite.is_empty(), "non-finite outputs");
    assert!(t.run_over_limit.is_empty(), "runs over {limit} s");
    assert!(
        t.run_errors_without_key.is_empty(),
        "run failures whose message names no key"
    );
}
