//! Range checks shared by every scenario kind: physical ranges of lengths, moduli, densities,
//! masses, speeds, time steps, durations and tolerances, and limits of every count (grid
//! elements, modes, beam elements, wheels, steps, output rows) checked against the memory they
//! need *before* anything is allocated.
//!
//! The ranges are wide (they refuse values no physical scenario has, such as `1e-300` m or a
//! modulus of `1e300` Pa, not unusual ones); the error names the key as written in the file,
//! the value and the allowed range.

use super::ConfigError;

/// Largest memory a scenario may ask for before it is refused \[bytes\] (4 GiB).
pub const MAX_MEMORY_BYTES: f64 = 4.0 * 1024.0 * 1024.0 * 1024.0;
/// Largest number of time steps of a fixed-step run (at ≥ 1 µs per step, over a day of work).
pub const MAX_STEPS: f64 = 1e8;
/// Largest number of recorded output rows (samples) of a run.
pub const MAX_OUTPUT_ROWS: f64 = 1e7;
/// Largest number of boundary elements of one contact grid (2048 × 2048).
pub const MAX_GRID_ELEMENTS: usize = 2048 * 2048;
/// Largest number of elements along one side of a contact grid.
pub const MAX_GRID_SIDE: usize = 65_536;
/// Memory per boundary element of the normal and tangential solvers \[bytes\]: the influence
/// spectrum on the doubled grid (4 × 16 B), pressure, gap, CG vectors and work arrays.
pub const GRID_BYTES_PER_ELEMENT: f64 = 200.0;
/// Largest number of bridge modes.
pub const MAX_MODES: usize = 1000;
/// Largest number of finite elements of an FE bridge (the eigen-solve is dense in the
/// 2 (elements + 1) degrees of freedom).
pub const MAX_FE_ELEMENTS: usize = 2000;
/// Largest number of wheels of a vehicle.
pub const MAX_WHEELS: usize = 256;
/// Largest number of cosines of a random irregularity.
pub const MAX_IRREGULARITY_COMPONENTS: usize = 100_000;
/// Largest iteration limit of any solver.
pub const MAX_ITERATIONS: usize = 1_000_000;

/// The allowed range of a numeric key, with its unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// Lower bound.
    pub lo: f64,
    /// Upper bound (inclusive).
    pub hi: f64,
    /// `true`: `lo` itself is excluded.
    pub lo_open: bool,
    /// Unit as printed (SI).
    pub unit: &'static str,
}

impl Range {
    /// `[lo, hi]`.
    pub const fn closed(lo: f64, hi: f64, unit: &'static str) -> Self {
        Self {
            lo,
            hi,
            lo_open: false,
            unit,
        }
    }

    /// `(lo, hi]`.
    pub const fn above(lo: f64, hi: f64, unit: &'static str) -> Self {
        Self {
            lo,
            hi,
            lo_open: true,
            unit,
        }
    }

    /// `[-bound, bound]`.
    pub const fn symmetric(bound: f64, unit: &'static str) -> Self {
        Self::closed(-bound, bound, unit)
    }

    /// `true` when `v` is finite and inside the range.
    pub fn contains(&self, v: f64) -> bool {
        v.is_finite()
            && v <= self.hi
            && if self.lo_open {
                v > self.lo
            } else {
                v >= self.lo
            }
    }

    /// `v`, or an error naming `key`, the value and the range.
    pub fn check(&self, key: &str, v: f64) -> Result<f64, ConfigError> {
        if self.contains(v) {
            return Ok(v);
        }
        let what = if v.is_finite() {
            "must lie in"
        } else {
            "must be a finite number in"
        };
        Err(ConfigError::Invalid(format!(
            "`{key}` = {}: {what} {self}",
            number(v)
        )))
    }

    /// [`Range::check`] of an optional key.
    pub fn check_opt(&self, key: &str, v: Option<f64>) -> Result<Option<f64>, ConfigError> {
        v.map(|v| self.check(key, v)).transpose()
    }
}

impl std::fmt::Display for Range {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let open = if self.lo_open { "(" } else { "[" };
        write!(f, "{open}{}, {}]", number(self.lo), number(self.hi))?;
        if !self.unit.is_empty() {
            write!(f, " {}", self.unit)?;
        }
        Ok(())
    }
}

/// A number as printed in messages: plain for moderate magnitudes, scientific otherwise.
pub fn number(v: f64) -> String {
    if v == 0.0 || (v.is_finite() && (1e-4..1e6).contains(&v.abs())) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// Physical ranges used by the scenario kinds (SI units).
pub mod ranges {
    use super::Range;

    /// A span, a bridge section, a wavelength or an irregularity length.
    pub const SPAN: Range = Range::above(0.0, 1e4, "m");
    /// A position along the track or the span (may be negative: before the span).
    pub const POSITION: Range = Range::symmetric(1e6, "m");
    /// A radius of curvature of a contact body (wheel, rail head, ball, gap radii).
    pub const RADIUS: Range = Range::closed(1e-9, 1e6, "m");
    /// A boundary-element size.
    pub const ELEMENT_SIZE: Range = Range::closed(
        halfspace::grid::ELEMENT_SIZE_RANGE.0,
        halfspace::grid::ELEMENT_SIZE_RANGE.1,
        "m",
    );
    /// A grid origin.
    pub const ORIGIN: Range = Range::symmetric(1e3, "m");
    /// A gap curvature coefficient A, B (gap = A x² + B y²).
    pub const CURVATURE: Range = Range::closed(0.0, 1e12, "1/m");
    /// Young's modulus of a contact body or a beam.
    pub const MODULUS: Range = Range::closed(1.0, 1e13, "Pa");
    /// Bending stiffness EI.
    pub const BENDING_STIFFNESS: Range = Range::closed(
        beam::error::BENDING_STIFFNESS_RANGE.0,
        beam::error::BENDING_STIFFNESS_RANGE.1,
        "N m²",
    );
    /// Second moment of area I.
    pub const SECOND_MOMENT: Range = Range::closed(1e-24, 1e4, "m⁴");
    /// Mass per unit length ρA.
    pub const MASS_PER_LENGTH: Range = Range::closed(1e-6, 1e7, "kg/m");
    /// A mass that may be zero (a massless wheel, no body, no point mass).
    pub const MASS_OR_ZERO: Range = Range::closed(0.0, 1e8, "kg");
    /// A vehicle mass (wheel, body) when it is not zero: a gram to 100,000 t (a tiny positive
    /// mass is a typo or an overflow, and makes the step matrix singular).
    pub const VEHICLE_MASS: Range = Range::closed(1e-3, 1e8, "kg");
    /// A mass that must be positive.
    pub const MASS: Range = Range::above(0.0, 1e8, "kg");
    /// A rotary or polar inertia.
    pub const INERTIA: Range = Range::closed(0.0, 1e8, "kg m²");
    /// A density.
    pub const DENSITY: Range = Range::closed(1e-3, 1e5, "kg/m³");
    /// A spring stiffness (suspension, bearing).
    pub const STIFFNESS: Range = Range::closed(0.0, 1e15, "N/m");
    /// A rotational spring stiffness.
    pub const ROTATIONAL_STIFFNESS: Range = Range::closed(0.0, 1e15, "N m/rad");
    /// A viscous damping coefficient.
    pub const DAMPER: Range = Range::closed(0.0, 1e12, "N s/m");
    /// A force (either sign).
    pub const FORCE: Range = Range::symmetric(1e12, "N");
    /// A torque (either sign).
    pub const TORQUE: Range = Range::symmetric(1e9, "N m");
    /// A vehicle or load speed.
    pub const SPEED: Range = Range::above(0.0, 1e3, "m/s");
    /// An initial velocity (either sign).
    pub const VELOCITY: Range = Range::symmetric(1e4, "m/s");
    /// A time step.
    pub const TIME_STEP: Range = Range::closed(1e-12, 1.0, "s");
    /// A simulated duration.
    pub const DURATION: Range = Range::above(0.0, 1e6, "s");
    /// A relative tolerance.
    pub const TOLERANCE: Range = Range::closed(1e-16, 0.5, "");
    /// An absolute tolerance (scaled by the state's unit).
    pub const ABS_TOLERANCE: Range = Range::closed(1e-30, 1.0, "");
    /// A modal damping ratio.
    pub const DAMPING_RATIO: Range = Range::closed(0.0, 10.0, "");
    /// Gravitational acceleration.
    pub const GRAVITY: Range = Range::closed(0.0, 1e4, "m/s²");
    /// A height or depth of a rail irregularity, a rigid approach or shift.
    pub const SMALL_DISPLACEMENT: Range = Range::symmetric(1.0, "m");
    /// A friction coefficient.
    pub const FRICTION: Range = Range::above(0.0, 10.0, "");
    /// A creepage (dimensionless).
    pub const CREEPAGE: Range = Range::symmetric(1.0, "");
    /// A spin creepage.
    pub const SPIN: Range = Range::symmetric(1e4, "1/m");
}

/// A count in `[lo, hi]`, or an error naming `key` (checked before anything is allocated).
pub fn count(key: &str, n: usize, lo: usize, hi: usize) -> Result<usize, ConfigError> {
    if n < lo {
        return Err(ConfigError::Invalid(format!(
            "`{key}` = {n}: must be at least {lo} (allowed {lo} … {hi})"
        )));
    }
    if n > hi {
        return Err(ConfigError::TooLarge(format!(
            "`{key}` = {n}: at most {hi} is allowed (allowed {lo} … {hi})"
        )));
    }
    Ok(n)
}

/// Refuse `what` when `items × bytes_each` exceeds [`MAX_MEMORY_BYTES`]; the message states
/// the estimate.
pub fn memory(what: &str, items: f64, bytes_each: f64) -> Result<(), ConfigError> {
    let bytes = items * bytes_each;
    if bytes.is_finite() && bytes <= MAX_MEMORY_BYTES {
        return Ok(());
    }
    Err(ConfigError::TooLarge(format!(
        "{what} would need about {} of memory (limit {})",
        bytes_text(bytes),
        bytes_text(MAX_MEMORY_BYTES)
    )))
}

/// Refuse a run of `steps` time steps (`what` names the keys that set it).
pub fn steps(what: &str, steps: f64) -> Result<f64, ConfigError> {
    if steps.is_finite() && steps <= MAX_STEPS {
        return Ok(steps);
    }
    Err(ConfigError::TooLarge(format!(
        "{what} gives about {} time steps; at most {} are allowed (shorten the run or enlarge the step)",
        number(steps),
        number(MAX_STEPS)
    )))
}

/// Refuse more than [`MAX_OUTPUT_ROWS`] recorded samples.
pub fn output_rows(what: &str, rows: f64) -> Result<f64, ConfigError> {
    if rows.is_finite() && rows <= MAX_OUTPUT_ROWS {
        return Ok(rows);
    }
    Err(ConfigError::TooLarge(format!(
        "{what} gives about {} output rows; at most {} are allowed",
        number(rows),
        number(MAX_OUTPUT_ROWS)
    )))
}

/// A contact grid of `nx × ny` elements (`key` names its keys): side and total limits and
/// the memory of the solvers.
pub fn grid(key: &str, nx: usize, ny: usize) -> Result<(), ConfigError> {
    for n in [nx, ny] {
        count(key, n, 1, MAX_GRID_SIDE)?;
    }
    let total = nx as f64 * ny as f64;
    if total > MAX_GRID_ELEMENTS as f64 {
        return Err(ConfigError::TooLarge(format!(
            "`{key}`: a {nx} × {ny} grid has {} elements, at most {MAX_GRID_ELEMENTS} are allowed (about {} of memory)",
            number(total),
            bytes_text(total * GRID_BYTES_PER_ELEMENT)
        )));
    }
    memory(
        &format!("`{key}` ({nx} × {ny} elements)"),
        total,
        GRID_BYTES_PER_ELEMENT,
    )
}

fn bytes_text(bytes: f64) -> String {
    if !bytes.is_finite() {
        return "an unbounded amount".into();
    }
    let gb = bytes / 1e9;
    if gb >= 1.0 {
        format!("{} GB", number((gb * 10.0).round() / 10.0))
    } else {
        format!("{:.0} MB", bytes / 1e6)
    }
}

/// Largest number of response points of `[output] points` (every scenario kind).
pub const MAX_POINTS: usize = 1000;

/// `output.points`: between `min` and [`MAX_POINTS`] positions, each on the span [0, `length`]
/// (the error names the point's index, its value and the range).
pub fn points_on_span(points: &[f64], min: usize, length: f64) -> Result<Vec<f64>, ConfigError> {
    count("output.points", points.len(), min, MAX_POINTS)?;
    for (i, &x) in points.iter().enumerate() {
        if !(x.is_finite() && (0.0..=length).contains(&x)) {
            return Err(ConfigError::Invalid(format!(
                "`output.points[{i}]` = {}: must lie on the span [0, {length}] m",
                number(x)
            )));
        }
    }
    Ok(points.to_vec())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn range_messages_name_key_value_and_range() {
        let e = ranges::BENDING_STIFFNESS
            .check("bridge.EI", 1e-300)
            .unwrap_err()
            .to_string();
        assert_eq!(e, "`bridge.EI` = 1e-300: must lie in [1e-6, 1e14] N m²");
        let e = ranges::SPEED.check("vehicle.speed", f64::NAN).unwrap_err();
        assert!(e.to_string().contains("finite"), "{e}");
        assert_eq!(ranges::SPEED.check("v", 30.0).unwrap(), 30.0);
        assert!(ranges::SPEED.check("v", 0.0).is_err(), "open at 0");
        assert!(ranges::MASS_OR_ZERO.check("m", 0.0).is_ok(), "closed at 0");
    }

    #[test]
    fn sizes_are_refused_with_an_estimate() {
        let e = grid("grid.nx", 44_000_000, 1).unwrap_err().to_string();
        assert!(e.contains("grid.nx") && e.contains("65536"), "{e}");
        let e = grid("grid.nx", 4096, 4096).unwrap_err().to_string();
        assert!(e.contains("GB"), "{e}");
        assert!(grid("grid", 64, 64).is_ok());
        let e = steps("integrator.duration / integrator.dt", 1e12)
            .unwrap_err()
            .to_string();
        assert!(e.contains("1e12"), "{e}");
        assert!(count("bridge.modes", 0, 1, MAX_MODES).is_err());
        assert!(
            memory("x", 1e12, 8.0)
                .unwrap_err()
                .to_string()
                .contains("GB")
        );
    }
}
