//! Output files of a run.
//!
//! A run owns its output set: [`RunOutput::create`] probes `--out` before any work (it must be
//! a directory we can write into; its parent must exist) and makes a private directory
//! `.dyncontact-run-PID-NANOS` inside it. Every file of the run is written there;
//! [`RunOutput::commit`] then takes the lock `--out/.dyncontact.lock`, removes the previous
//! run's files of the same set and moves the new files in. A killed run therefore never leaves
//! a new `timeseries.csv` beside an old `summary.json`, and two runs writing into one directory
//! at once never interleave their files (the later commit replaces the earlier set whole).
//! An incomplete run (interrupted) is committed with its incrementally written files renamed
//! `NAME.partial.EXT` and `"completed": false` in its summary.

use std::fs::{self, File};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::time::{SystemTime, UNIX_EPOCH};

use anyhow::{Context, Result};
use serde::Serialize;

use crate::errors::BadInput;

/// Prefix of the private per-run directories inside `--out`.
const RUN_DIR_PREFIX: &str = ".dyncontact-run-";
/// The lock file held while a run's set is moved into `--out`.
const LOCK_FILE: &str = ".dyncontact.lock";

/// The sibling name that marks a file incomplete: `NAME.partial.EXT`.
pub fn partial_name(name: &str) -> String {
    match name.rsplit_once('.') {
        Some((stem, ext)) => format!("{stem}.partial.{ext}"),
        None => format!("{name}.partial"),
    }
}

/// The files of one run, written into a private directory and moved into `--out` at the end.
pub struct RunOutput {
    dir: PathBuf,
    private: PathBuf,
    set: &'static [&'static str],
    committed: bool,
}

impl RunOutput {
    /// Probe `dir` (create it if only the last component is missing) and make the run's
    /// private directory. `set` names every file this kind of run may write (the previous
    /// run's files of these names are replaced at commit). Errors are [`BadInput`].
    pub fn create(dir: &Path, set: &'static [&'static str]) -> Result<Self> {
        let shown = dir.display();
        if dir.exists() && !dir.is_dir() {
            return Err(BadInput::error(format!(
                "--out {shown}: exists and is not a directory"
            )));
        }
        if !dir.exists() {
            let parent = dir
                .parent()
                .filter(|p| !p.as_os_str().is_empty())
                .unwrap_or(Path::new("."));
            if !parent.is_dir() {
                return Err(BadInput::error(format!(
                    "--out {shown}: the parent directory {} does not exist",
                    parent.display()
                )));
            }
            // A concurrent run may create it between the check and here: that is fine.
            match fs::create_dir(dir) {
                Err(e) if !(e.kind() == std::io::ErrorKind::AlreadyExists && dir.is_dir()) => {
                    return Err(BadInput::error(format!(
                        "--out {shown}: cannot create the directory: {e}"
                    )));
                }
                _ => {}
            }
        }
        let nanos = SystemTime::now()
            .duration_since(UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos());
        let private = dir.join(format!("{RUN_DIR_PREFIX}{}-{nanos}", std::process::id()));
        fs::create_dir(&private).map_err(|e| {
            BadInput::error(format!("--out {shown}: the directory is not writable: {e}"))
        })?;
        let run = RunOutput {
            dir: dir.to_path_buf(),
            private,
            set,
            committed: false,
        };
        // Probe-write: a file with some content, so a full disk shows now, not after the run.
        let probe = run.private.join(".probe");
        fs::write(&probe, [0u8; 4096])
            .and_then(|()| fs::remove_file(&probe))
            .map_err(|e| BadInput::error(format!("--out {shown}: cannot write into it: {e}")))?;
        Ok(run)
    }

    /// Where the run writes file `name` (inside its private directory).
    pub fn path(&self, name: &str) -> PathBuf {
        debug_assert!(self.set.contains(&name), "{name} is not in the output set");
        self.private.join(name)
    }

    /// Rename the finished file `name` to `NAME.partial.EXT` (the run did not complete).
    pub fn mark_partial(&self, name: &str) -> Result<()> {
        let from = self.private.join(name);
        if from.exists() {
            fs::rename(&from, self.private.join(partial_name(name)))
                .with_context(|| format!("cannot mark {} partial", from.display()))?;
        }
        Ok(())
    }

    /// Move the run's files into `--out` under the lock, replacing the previous set.
    pub fn commit(mut self) -> Result<()> {
        let lock = File::create(self.dir.join(LOCK_FILE))
            .with_context(|| format!("cannot create the lock file in {}", self.dir.display()))?;
        lock.lock()
            .with_context(|| format!("cannot lock {}", self.dir.display()))?;
        for name in self.set {
            for old in [name.to_string(), partial_name(name)] {
                let path = self.dir.join(&old);
                if path.exists() {
                    fs::remove_file(&path).with_context(|| {
                        format!("cannot remove the previous run's {}", path.display())
                    })?;
                }
            }
        }
        for entry in fs::read_dir(&self.private)
            .with_context(|| format!("cannot list {}", self.private.display()))?
        {
            let entry = entry?;
            let target = self.dir.join(entry.file_name());
            fs::rename(entry.path(), &target)
                .with_context(|| format!("cannot move {} into place", target.display()))?;
        }
        fs::remove_dir(&self.private)
            .with_context(|| format!("cannot remove {}", self.private.display()))?;
        self.committed = true;
        remove_stale_run_dirs(&self.dir);
        drop(lock);
        Ok(())
    }
}

impl Drop for RunOutput {
    fn drop(&mut self) {
        if !self.committed {
            let _ = fs::remove_dir_all(&self.private);
        }
    }
}

/// Private directories left by runs that were killed (their process no longer exists).
fn remove_stale_run_dirs(dir: &Path) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let Some(pid) = name
            .strip_prefix(RUN_DIR_PREFIX)
            .and_then(|rest| rest.split('-').next())
            .and_then(|pid| pid.parse::<i32>().ok())
        else {
            continue;
        };
        if !process_alive(pid) {
            let _ = fs::remove_dir_all(entry.path());
        }
    }
}

fn process_alive(pid: i32) -> bool {
    #[cfg(unix)]
    {
        // SAFETY: kill with signal 0 only checks whether the process exists.
        let r = unsafe { libc::kill(pid, 0) };
        r == 0 || std::io::Error::last_os_error().raw_os_error() != Some(libc::ESRCH)
    }
    #[cfg(not(unix))]
    {
        let _ = pid;
        true
    }
}

/// The temporary sibling of `path`: `.NAME.partial.EXT` (the extension is kept because the
/// plotting back-end chooses its encoder from it).
fn partial_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{}", partial_name(&name)))
}

/// Write `path` atomically: `write` produces the temporary file, which is renamed on success
/// and removed on failure.
pub fn write_atomic(path: &Path, write: impl FnOnce(&Path) -> Result<()>) -> Result<()> {
    let tmp = partial_path(path);
    match write(&tmp) {
        Ok(()) => fs::rename(&tmp, path)
            .with_context(|| format!("cannot move {} into place", path.display())),
        Err(e) => {
            let _ = fs::remove_file(&tmp);
            Err(e.context(format!("cannot write {}", path.display())))
        }
    }
}

/// The scenario the run read: its name and its text (echoed in `summary.json`).
static INPUT: std::sync::OnceLock<(String, String)> = std::sync::OnceLock::new();

/// Record the scenario file of this run (set once, by `main`), for [`write_summary`].
pub fn set_input(name: impl Into<String>, text: impl Into<String>) {
    let _ = INPUT.set((name.into(), text.into()));
}

/// The name of the scenario file recorded by [`set_input`], if any.
pub fn input_name() -> Option<String> {
    INPUT.get().map(|(name, _)| name.clone())
}

/// Write a run's `summary.json`: the value as by [`write_json`], plus `"input"`: the scenario
/// file's name (`file`) and every key it set, as given (`scenario`, the TOML as JSON; defaults
/// the file left out are not listed), so the summary says what produced it.
pub fn write_summary<T: Serialize>(path: &Path, value: &T) -> Result<()> {
    let mut json: serde_json::Value = serde_json::from_str(&json_text(value)?)?;
    if let (Some((name, text)), serde_json::Value::Object(map)) = (INPUT.get(), &mut json) {
        let scenario = text
            .parse::<toml::Table>()
            .ok()
            .and_then(|t| serde_json::to_value(t).ok())
            .unwrap_or(serde_json::Value::Null);
        map.insert(
            "input".into(),
            serde_json::json!({ "file": name, "scenario": scenario }),
        );
    }
    write_atomic(path, |tmp| {
        fs::write(tmp, serde_json::to_string_pretty(&json)? + "\n")?;
        Ok(())
    })
}

/// Write a value as pretty JSON, atomically (non-finite numbers: see [`json_text`]).
pub fn write_json<T: Serialize>(path: &Path, value: &T) -> Result<()> {
    write_atomic(path, |tmp| {
        fs::write(tmp, json_text(value)? + "\n")?;
        Ok(())
    })
}

/// Pretty JSON of `value`. JSON has no NaN or infinity: serde_json writes them as `null`; the
/// fields where that happened are listed under `"non_finite"` (with the reason) so a `null`
/// never silently stands for a failed computation.
pub fn json_text<T: Serialize>(value: &T) -> Result<String> {
    let mut json = serde_json::to_value(value)?;
    let mut bad = Vec::new();
    if let Ok(t) = toml::Value::try_from(value) {
        non_finite_paths(&t, String::new(), &mut bad);
    }
    if !bad.is_empty()
        && let serde_json::Value::Object(map) = &mut json
    {
        map.insert(
            "non_finite".into(),
            serde_json::json!({
                "fields": bad,
                "reason": "the value was NaN or infinite (not representable in JSON); written as null",
            }),
        );
    }
    Ok(serde_json::to_string_pretty(&json)?)
}

/// Dotted paths of the NaN / infinite floats in `v` (TOML keeps them, JSON cannot).
fn non_finite_paths(v: &toml::Value, at: String, out: &mut Vec<String>) {
    match v {
        toml::Value::Float(x) if !x.is_finite() => out.push(at),
        toml::Value::Array(items) => {
            for (k, item) in items.iter().enumerate() {
                non_finite_paths(item, format!("{at}[{k}]"), out);
            }
        }
        toml::Value::Table(t) => {
            for (key, item) in t {
                let path = if at.is_empty() {
                    key.clone()
                } else {
                    format!("{at}.{key}")
                };
                non_finite_paths(item, path, out);
            }
        }
        _ => {}
    }
}

/// "1 step", "2 steps": `n` and the noun, plural when n ≠ 1 (every count the CLI prints).
pub fn plural(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("{n} {noun}")
    } else {
        format!("{n} {noun}s")
    }
}

/// Write a CSV file with a header and numeric rows, atomically.
pub fn write_csv(
    path: &Path,
    header: &[&str],
    rows: impl IntoIterator<Item = Vec<f64>>,
) -> Result<()> {
    write_atomic(path, |tmp| {
        let mut w = CsvStream::create(tmp, header)?;
        for row in rows {
            w.row(&row)?;
        }
        w.finish()
    })
}

/// A CSV file written row by row as a run advances (never held in memory whole). Numbers are
/// written in Rust's shortest round-trip exponent form (`1.5e-3`).
pub struct CsvStream {
    path: PathBuf,
    w: BufWriter<File>,
    line: String,
}

impl CsvStream {
    /// Create the file and write the header.
    pub fn create(path: &Path, header: &[&str]) -> Result<Self> {
        let file =
            File::create(path).with_context(|| format!("cannot create {}", path.display()))?;
        let mut s = CsvStream {
            path: path.to_path_buf(),
            w: BufWriter::with_capacity(1 << 16, file),
            line: String::new(),
        };
        s.line = header.join(",");
        s.line.push('\n');
        s.flush_line()?;
        Ok(s)
    }

    fn flush_line(&mut self) -> Result<()> {
        let r = self.w.write_all(self.line.as_bytes());
        r.with_context(|| format!("cannot write {}", self.path.display()))
    }

    /// Append one row.
    pub fn row(&mut self, values: &[f64]) -> Result<()> {
        use std::fmt::Write as _;
        self.line.clear();
        for (k, v) in values.iter().enumerate() {
            if k > 0 {
                self.line.push(',');
            }
            // Integral values (counts, iterations, states, flags) as integers; the rest in
            // exponent form with every digit of the f64.
            if v.is_finite() && v.fract() == 0.0 && v.abs() < 9.0e15 {
                let _ = write!(self.line, "{}", *v as i64);
            } else {
                let _ = write!(self.line, "{v:e}");
            }
        }
        self.line.push('\n');
        self.flush_line()
    }

    /// Flush and sync to disk (a full disk shows here at the latest, naming the file).
    pub fn finish(mut self) -> Result<()> {
        self.w
            .flush()
            .and_then(|()| self.w.get_ref().sync_all())
            .with_context(|| format!("cannot write {}", self.path.display()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn failed_write_leaves_no_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.csv");
        let r = write_atomic(&path, |tmp| {
            fs::write(tmp, "half")?;
            anyhow::bail!("interrupted")
        });
        assert!(r.is_err());
        assert!(!path.exists());
        assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 0);
        write_csv(
            &path,
            &["a", "b", "c", "d"],
            vec![vec![1.0, 2.5, -0.0, f64::NAN]],
        )
        .unwrap();
        // Integral values as integers, the rest in full-precision exponent form.
        assert_eq!(
            fs::read_to_string(&path).unwrap(),
            "a,b,c,d\n1,2.5e0,0,NaN\n"
        );
    }

    #[test]
    fn commit_replaces_the_previous_set_and_drop_leaves_nothing() {
        const SET: &[&str] = &["a.csv", "b.json"];
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        fs::create_dir(&out).unwrap();
        fs::write(out.join("b.json"), "old").unwrap();
        fs::write(out.join("a.partial.csv"), "old").unwrap();
        fs::write(out.join("keep.txt"), "not ours").unwrap();
        // An abandoned run leaves nothing behind.
        let run = RunOutput::create(&out, SET).unwrap();
        fs::write(run.path("a.csv"), "x").unwrap();
        drop(run);
        let names = |d: &Path| {
            let mut v: Vec<String> = fs::read_dir(d)
                .unwrap()
                .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .collect();
            v.sort();
            v
        };
        assert_eq!(names(&out), ["a.partial.csv", "b.json", "keep.txt"]);
        // A committed run replaces the whole set (the old b.json and a.partial.csv go).
        let run = RunOutput::create(&out, SET).unwrap();
        fs::write(run.path("a.csv"), "new").unwrap();
        run.commit().unwrap();
        assert_eq!(names(&out), [".dyncontact.lock", "a.csv", "keep.txt"]);
        // An incomplete run is committed with its file marked partial.
        let run = RunOutput::create(&out, SET).unwrap();
        fs::write(run.path("a.csv"), "half").unwrap();
        run.mark_partial("a.csv").unwrap();
        run.commit().unwrap();
        assert_eq!(
            names(&out),
            [".dyncontact.lock", "a.partial.csv", "keep.txt"]
        );
    }

    #[test]
    fn unusable_out_is_bad_input() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("file");
        fs::write(&file, "x").unwrap();
        for (out, says) in [
            (file.clone(), "not a directory"),
            (dir.path().join("missing/out"), "does not exist"),
        ] {
            let e = RunOutput::create(&out, &["a.csv"]).err().unwrap();
            assert!(e.downcast_ref::<BadInput>().is_some());
            let text = format!("{e:#}");
            assert!(
                text.contains(&*out.to_string_lossy()) && text.contains(says),
                "{text}"
            );
        }
    }

    /// A full disk (Linux's /dev/full answers every write with ENOSPC): the error names the file.
    #[cfg(target_os = "linux")]
    #[test]
    fn full_disk_error_names_the_file() {
        let full = Path::new("/dev/full");
        let mut w = CsvStream::create(full, &["t", "x"]).unwrap();
        let mut failed = None;
        for _ in 0..10_000 {
            if let Err(e) = w.row(&[1.0, 2.0]) {
                failed = Some(e);
                break;
            }
        }
        let e = match failed {
            Some(e) => e,
            None => w.finish().unwrap_err(),
        };
        let text = format!("{e:#}");
        assert!(text.contains("cannot write /dev/full"), "{text}");
        assert!(text.contains("No space left"), "{text}");
    }

    #[test]
    fn non_finite_numbers_are_listed() {
        #[derive(Serialize)]
        struct Inner {
            x: f64,
        }
        #[derive(Serialize)]
        struct S {
            a: f64,
            inner: Inner,
            ok: Option<f64>,
        }
        let text = json_text(&S {
            a: f64::NAN,
            inner: Inner { x: f64::INFINITY },
            ok: None,
        })
        .unwrap();
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert!(v["a"].is_null() && v["inner"]["x"].is_null());
        assert_eq!(
            v["non_finite"]["fields"],
            serde_json::json!(["a", "inner.x"])
        );
        let clean = json_text(&Inner { x: 1.0 }).unwrap();
        assert!(!clean.contains("non_finite"));
    }
}
