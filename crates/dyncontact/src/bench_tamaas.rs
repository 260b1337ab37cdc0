//! The comparison of `dyncontact bench contact` with tamaas, a Python FFT contact library
//! (references.md §R4.4), run on the same Hertz case in the same run when it is installed.
//!
//! tamaas is not a dependency: the bench starts the Python interpreter named by the
//! environment variable `DYNCONTACT_PYTHON` (default `python3`) on the script below. A missing
//! interpreter, a missing `tamaas` or `numpy` module or a failed run is reported in one line and
//! the comparison skipped; the bench itself does not fail.

use std::process::Command;

/// The Python side: the bench's Hertz case (combined modulus E/(2(1 − ν²)) of two equal
/// bodies, sphere R, force F) on an n × n grid of the given width, solved by tamaas's
/// `PolonskyKeerRey` to its tolerance `tol`, a new model for each of three cold solves (tamaas
/// keeps its last pressure), best wall time inside Python (imports and set-up of the gap
/// excluded). Exit code 3 when a module is missing. Last line:
/// `RESULT seconds p0 force`, tamaas's maximum pressure and total force.
const SCRIPT: &str = r#"
import sys, time
try:
    import numpy as np
    import tamaas as tm
except ImportError as e:
    print(e, file=sys.stderr)
    sys.exit(3)
n, width, e, nu, radius, force, tol = int(sys.argv[1]), *map(float, sys.argv[2:8])
dx = width / n
x = (np.arange(n) + 0.5) * dx - width / 2
xx, yy = np.meshgrid(x, x, indexing="ij")
surface = -((xx**2 + yy**2) / (2 * radius))
best = float("inf")
for _ in range(3):
    t0 = time.perf_counter()
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [width, width], [n, n])
    model.E = e / 2
    model.nu = nu
    solver = tm.PolonskyKeerRey(model, surface, tol)
    solver.dump_freq = 10**9
    solver.solve(force / (width * width))
    best = min(best, time.perf_counter() - t0)
p = model.traction
print("VERSION", tm.__version__)
print("RESULT", best, float(p.max()), float(p.sum()) * dx * dx)
"#;

/// What the comparison found.
#[derive(Debug)]
pub enum Outcome {
    /// tamaas ran: its version, best wall time \[s\], maximum pressure \[Pa\], total force \[N\].
    Measured {
        version: String,
        seconds: f64,
        max_pressure: f64,
        force: f64,
    },
    /// Not run, with the reason (one line).
    Skipped(String),
}

/// The Hertz case of the bench: grid `n` × `n` over a square of side `width` \[m\], Young's
/// modulus `e` \[Pa\] and Poisson's ratio `nu` of both bodies, sphere radius \[m\], force \[N\],
/// and tamaas's tolerance.
pub struct Case {
    pub n: usize,
    pub width: f64,
    pub e: f64,
    pub nu: f64,
    pub radius: f64,
    pub force: f64,
    pub tol: f64,
}

/// Run tamaas on `case` (module documentation).
pub fn run(case: &Case) -> Outcome {
    let python = std::env::var("DYNCONTACT_PYTHON").unwrap_or_else(|_| "python3".into());
    let output = Command::new(&python)
        .arg("-c")
        .arg(SCRIPT)
        .arg(case.n.to_string())
        .args(
            [
                case.width,
                case.e,
                case.nu,
                case.radius,
                case.force,
                case.tol,
            ]
            .map(|v| format!("{v:e}")),
        )
        .output();
    let output = match output {
        Ok(o) => o,
        Err(e) => {
            return Outcome::Skipped(format!(
                "no Python interpreter `{python}` ({e}; set DYNCONTACT_PYTHON)"
            ));
        }
    };
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    if output.status.code() == Some(3) {
        return Outcome::Skipped(format!(
            "tamaas (or numpy) is not importable by `{python}` ({}; `pip install tamaas` to compare, not a dependency)",
            stderr.trim()
        ));
    }
    let last_err = || stderr.lines().last().unwrap_or("").trim().to_string();
    if !output.status.success() {
        return Outcome::Skipped(format!("tamaas failed ({}): {}", output.status, last_err()));
    }
    let version = stdout
        .lines()
        .find_map(|l| l.strip_prefix("VERSION "))
        .unwrap_or("?")
        .to_string();
    let values: Option<Vec<f64>> =
        stdout
            .lines()
            .find_map(|l| l.strip_prefix("RESULT "))
            .map(|l| {
                l.split_whitespace()
                    .filter_map(|v| v.parse().ok())
                    .collect()
            });
    match values.as_deref() {
        Some(&[seconds, max_pressure, force]) => Outcome::Measured {
            version,
            seconds,
            max_pressure,
            force,
        },
        _ => Outcome::Skipped(format!("tamaas printed no result line ({})", last_err())),
    }
}
