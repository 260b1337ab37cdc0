//! Output files: every file is written under a temporary name in the same directory and
//! renamed when complete, so an interrupted run never leaves a file that looks finished.

use std::fs;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use serde::Serialize;

/// Create the output directory (and parents).
pub fn ensure_dir(dir: &Path) -> Result<()> {
    fs::create_dir_all(dir)
        .with_context(|| format!("cannot create output directory {}", dir.display()))
}

/// The temporary sibling of `path`: `.NAME.partial.EXT` (the extension is kept because the
/// plotting back-end chooses its encoder from it).
fn partial_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let partial = match name.rsplit_once('.') {
        Some((stem, ext)) => format!(".{stem}.partial.{ext}"),
        None => format!(".{name}.partial"),
    };
    path.with_file_name(partial)
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

/// Write a value as pretty JSON, atomically.
pub fn write_json<T: Serialize>(path: &Path, value: &T) -> Result<()> {
    write_atomic(path, |tmp| {
        let text = serde_json::to_string_pretty(value)?;
        fs::write(tmp, text + "\n")?;
        Ok(())
    })
}

/// Write a CSV file with a header and numeric rows, atomically.
pub fn write_csv(
    path: &Path,
    header: &[&str],
    rows: impl IntoIterator<Item = Vec<f64>>,
) -> Result<()> {
    write_atomic(path, |tmp| {
        let mut w = csv::Writer::from_path(tmp)?;
        w.write_record(header)?;
        for row in rows {
            w.write_record(row.iter().map(|v| format!("{v:e}")))?;
        }
        w.flush()?;
        Ok(())
    })
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
        write_csv(&path, &["a", "b"], vec![vec![1.0, 2.0]]).unwrap();
        assert_eq!(fs::read_to_string(&path).unwrap(), "a,b\n1e0,2e0\n");
    }
}
