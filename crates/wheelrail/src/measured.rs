//! Profiles from measured points: plain two-column text or CSV (y, z), and the point blocks
//! of SIMPACK/CONTACT profile files (`point.begin` … `point.end`, `units.len.f`); a cubic
//! smoothing spline through them (references.md §W1.3).
//!
//! The text parser takes a string (no file I/O). Comment lines start with `#`, `%`, `!` or
//! `//`; text after `!` is a comment (SIMPACK style). Values are separated by commas,
//! semicolons, tabs or spaces; the first two numbers of a line are y and z (a third column,
//! a SIMPACK weight, is ignored). One leading non-numeric line is a header. The profile must be
//! a function z(y): y strictly monotone (increasing or decreasing), which also excludes
//! self-intersections; every failure names the line and the value.
//!
//! The spline minimises Σ (z_i − f(y_i))² + λ ∫ f″(y)² dy (Reinsch 1967) with natural end
//! conditions; λ = 0 interpolates. λ is in m³ for y, z in metres: with points h apart it
//! smooths over a length of about L = (λ h)^{1/4}, so λ = L⁴/h (docs/profiles.md).

use crate::error::WheelRailError;
use crate::profile::{Profile, Segment};

/// Largest number of points of a profile.
pub const MAX_POINTS: usize = 100_000;

fn bad(line: usize, msg: String) -> WheelRailError {
    WheelRailError::InvalidProfile(format!("line {line}: {msg}"))
}

/// Points (y, z) of a profile text, in the file's units times `scale` (metres per unit;
/// a SIMPACK `units.len.f = F` line sets the scale to 1/F). Returns the points and the line
/// number of each.
pub fn parse_points(text: &str, scale: f64) -> Result<Vec<(f64, f64, usize)>, WheelRailError> {
    let has_block = text.lines().any(|l| l.trim() == "point.begin");
    let mut scale = scale;
    let mut inside = !has_block;
    let mut out = Vec::new();
    let mut header_seen = false;
    for (k, raw) in text.lines().enumerate() {
        let lineno = k + 1;
        let line = raw.split('!').next().unwrap_or("").trim();
        if line.is_empty()
            || line.starts_with('#')
            || line.starts_with('%')
            || line.starts_with("//")
        {
            continue;
        }
        if has_block {
            if let Some(v) = line
                .strip_prefix("units.len.f")
                .and_then(|r| r.trim().strip_prefix('='))
            {
                let f: f64 = v.trim().parse().map_err(|_| {
                    bad(
                        lineno,
                        format!("`units.len.f` = {}: not a number", v.trim()),
                    )
                })?;
                if !(f.is_finite() && f > 0.0) {
                    return Err(bad(
                        lineno,
                        format!("`units.len.f` = {f}: must be positive"),
                    ));
                }
                scale = 1.0 / f;
                continue;
            }
            if line == "point.begin" {
                inside = true;
                continue;
            }
            if line == "point.end" {
                inside = false;
                continue;
            }
            if !inside {
                continue;
            }
        }
        let fields: Vec<&str> = line
            .split(|c: char| c == ',' || c == ';' || c.is_whitespace())
            .filter(|s| !s.is_empty())
            .collect();
        let nums: Vec<Result<f64, _>> = fields.iter().take(2).map(|s| s.parse::<f64>()).collect();
        if nums.len() < 2 || nums.iter().any(|n| n.is_err()) {
            if !header_seen && out.is_empty() && !has_block {
                header_seen = true;
                continue;
            }
            return Err(bad(lineno, format!("`{line}`: expected two numbers y, z")));
        }
        let (y, z) = (
            *nums[0].as_ref().expect("checked"),
            *nums[1].as_ref().expect("checked"),
        );
        if !(y.is_finite() && z.is_finite()) {
            return Err(bad(lineno, format!("y = {y}, z = {z}: must be finite")));
        }
        out.push((y * scale, z * scale, lineno));
        if out.len() > MAX_POINTS {
            return Err(bad(lineno, format!("more than {MAX_POINTS} points")));
        }
    }
    if out.len() < 4 {
        return Err(WheelRailError::InvalidProfile(format!(
            "{} points: a profile needs at least 4",
            out.len()
        )));
    }
    Ok(out)
}

/// Points ordered by increasing y; an error names the first line where y is not strictly
/// monotone.
pub fn check_monotone(points: &[(f64, f64, usize)]) -> Result<Vec<(f64, f64)>, WheelRailError> {
    let increasing = points[points.len() - 1].0 > points[0].0;
    for w in points.windows(2) {
        let ok = if increasing {
            w[1].0 > w[0].0
        } else {
            w[1].0 < w[0].0
        };
        if !ok {
            return Err(bad(
                w[1].2,
                format!(
                    "y = {} after y = {} (line {}): y must be strictly {} (a profile z(y) without vertical parts or self-intersections)",
                    w[1].0,
                    w[0].0,
                    w[0].2,
                    if increasing {
                        "increasing"
                    } else {
                        "decreasing"
                    }
                ),
            ));
        }
    }
    let mut v: Vec<(f64, f64)> = points.iter().map(|p| (p.0, p.1)).collect();
    if !increasing {
        v.reverse();
    }
    Ok(v)
}

/// The smoothing spline of `points` (y increasing) with parameter `lambda` \[m³\].
pub fn smoothing_spline(
    name: &str,
    points: &[(f64, f64)],
    lambda: f64,
) -> Result<Profile, WheelRailError> {
    crate::error::in_range(
        "smoothing",
        lambda,
        0.0,
        1.0,
        "must lie in [0, 1] m³ (0 interpolates)",
    )?;
    let n = points.len();
    let y: Vec<f64> = points.iter().map(|p| p.0).collect();
    let z: Vec<f64> = points.iter().map(|p| p.1).collect();
    let h: Vec<f64> = y.windows(2).map(|w| w[1] - w[0]).collect();
    let m = n - 2;
    // Qᵀz and the matrix R + λ QᵀQ (pentadiagonal, m × m), interior knots 1 … n−2.
    let q = |i: usize| -> [f64; 3] {
        // Column i (interior knot k = i + 1): entries at rows k−1, k, k+1.
        let k = i + 1;
        [1.0 / h[k - 1], -1.0 / h[k - 1] - 1.0 / h[k], 1.0 / h[k]]
    };
    let mut rhs: Vec<f64> = (0..m)
        .map(|i| {
            let c = q(i);
            c[0] * z[i] + c[1] * z[i + 1] + c[2] * z[i + 2]
        })
        .collect();
    let mut a0 = vec![0.0; m];
    let mut a1 = vec![0.0; m.saturating_sub(1)];
    let mut a2 = vec![0.0; m.saturating_sub(2)];
    for i in 0..m {
        let k = i + 1;
        let ci = q(i);
        a0[i] = (h[k - 1] + h[k]) / 3.0 + lambda * (ci[0] * ci[0] + ci[1] * ci[1] + ci[2] * ci[2]);
        if i + 1 < m {
            let cj = q(i + 1);
            // Column i has rows k−1, k, k+1; column i+1 rows k, k+1, k+2.
            a1[i] = h[k] / 6.0 + lambda * (ci[1] * cj[0] + ci[2] * cj[1]);
        }
        if i + 2 < m {
            let cj = q(i + 2);
            a2[i] = lambda * (ci[2] * cj[0]);
        }
    }
    penta_cholesky_solve(&mut a0, &mut a1, &mut a2, &mut rhs);
    let gamma = rhs;
    // Fitted values a = z − λ Q γ.
    let mut fit = z.clone();
    for i in 0..m {
        let c = q(i);
        fit[i] -= lambda * c[0] * gamma[i];
        fit[i + 1] -= lambda * c[1] * gamma[i];
        fit[i + 2] -= lambda * c[2] * gamma[i];
    }
    let g = |k: usize| -> f64 {
        if k == 0 || k == n - 1 {
            0.0
        } else {
            gamma[k - 1]
        }
    };
    let segments = (0..n - 1)
        .map(|k| {
            let (g0, g1) = (g(k), g(k + 1));
            Segment::Cubic {
                y0: y[k],
                y1: y[k + 1],
                a: fit[k],
                b: (fit[k + 1] - fit[k]) / h[k] - h[k] * (2.0 * g0 + g1) / 6.0,
                c: 0.5 * g0,
                d: (g1 - g0) / (6.0 * h[k]),
            }
        })
        .collect();
    Profile::new(name, segments)
}

/// Banded Cholesky (bandwidth 2) of the SPD matrix with diagonals a0, a1, a2, then solve in
/// place.
fn penta_cholesky_solve(a0: &mut [f64], a1: &mut [f64], a2: &mut [f64], b: &mut [f64]) {
    let n = a0.len();
    // L: l0 (diagonal), l1 (sub-diagonal), l2 (second sub-diagonal), stored over a0, a1, a2.
    for i in 0..n {
        if i >= 2 {
            a2[i - 2] /= a0[i - 2];
        }
        if i >= 1 {
            let t = a1[i - 1]
                - if i >= 2 {
                    a2[i - 2] * a1[i - 2] * a0[i - 2]
                } else {
                    0.0
                };
            a1[i - 1] = t / a0[i - 1];
        }
        let mut d = a0[i];
        if i >= 1 {
            d -= a1[i - 1] * a1[i - 1] * a0[i - 1];
        }
        if i >= 2 {
            d -= a2[i - 2] * a2[i - 2] * a0[i - 2];
        }
        a0[i] = d;
    }
    // Forward: L y = b with unit lower L (LDLᵀ form: a0 holds D).
    for i in 0..n {
        if i >= 1 {
            b[i] -= a1[i - 1] * b[i - 1];
        }
        if i >= 2 {
            b[i] -= a2[i - 2] * b[i - 2];
        }
    }
    for i in 0..n {
        b[i] /= a0[i];
    }
    for i in (0..n).rev() {
        if i + 1 < n {
            b[i] -= a1[i] * b[i + 1];
        }
        if i + 2 < n {
            b[i] -= a2[i] * b[i + 2];
        }
    }
}

/// Which kind of profile a text describes (sets the orientation rules).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProfileKind {
    /// A wheel: z is the radius increase F(s), s from the tape circle. The flange is the
    /// extreme farthest from zero: if it is negative (a z-up file) z is negated, and if it
    /// lies at positive s the profile is mirrored, so that the flange is at negative s.
    Wheel,
    /// A rail head: z is the height. If the middle of the head lies below its ends (a z-down
    /// file, as CONTACT's), z is negated. The gauge side must be at negative y (a right rail).
    Rail,
}

/// A profile from text (`scale`: metres per file unit, 1e-3 for mm; a SIMPACK
/// `units.len.f` overrides it), oriented by `kind`'s rules and smoothed with `lambda` \[m³\].
pub fn parse_profile(
    name: &str,
    text: &str,
    kind: ProfileKind,
    scale: f64,
    lambda: f64,
) -> Result<Profile, WheelRailError> {
    crate::error::in_range(
        "scale",
        scale,
        1e-9,
        1.0,
        "must lie in [1e-9, 1] m per unit",
    )?;
    let raw = parse_points(text, scale)?;
    let mut pts = check_monotone(&raw)?;
    match kind {
        ProfileKind::Wheel => {
            let far = pts
                .iter()
                .copied()
                .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
                .expect("at least 4 points");
            if far.1 < 0.0 {
                for p in &mut pts {
                    p.1 = -p.1;
                }
            }
            let mid = 0.5 * (pts[0].0 + pts[pts.len() - 1].0);
            if far.0 > mid {
                pts = pts.iter().rev().map(|p| (-p.0, p.1)).collect();
            }
        }
        ProfileKind::Rail => {
            let mid = 0.5 * (pts[0].0 + pts[pts.len() - 1].0);
            let centre = pts
                .iter()
                .copied()
                .min_by(|a, b| (a.0 - mid).abs().total_cmp(&(b.0 - mid).abs()))
                .expect("at least 4 points");
            let ends = 0.5 * (pts[0].1 + pts[pts.len() - 1].1);
            if centre.1 < ends {
                for p in &mut pts {
                    p.1 = -p.1;
                }
            }
        }
    }
    smoothing_spline(name, &pts, lambda)
}

#[cfg(test)]
mod tests {
    use super::*;

    const MM: f64 = 1e-3;

    fn circle_text(r_mm: f64, noise_mm: f64) -> String {
        // A z-down circular head sampled every 0.5 mm over ±20 mm, with a deterministic
        // zero-mean disturbance of amplitude `noise_mm`.
        let mut s = String::from("y_mm, z_mm\n");
        for k in -40i64..=40 {
            let y = 0.5 * k as f64;
            let wobble = noise_mm * ((k * 7919).rem_euclid(13) as f64 / 6.0 - 1.0);
            let z = r_mm - (r_mm * r_mm - y * y).sqrt() + wobble;
            s.push_str(&format!("{y}, {z}\n"));
        }
        s
    }

    /// λ = 0 interpolates; on a 300 mm circle sampled every 0.5 mm the natural spline's
    /// curvature matches 1/R to 1e-4 relative away from the ends (the spline's error is
    /// O(h²) in the second derivative: (0.5/300)² ≈ 3e-6, ends excluded for the natural
    /// condition), and the z-down file is flipped to heights.
    #[test]
    fn interpolating_spline_recovers_a_circle() {
        let p = parse_profile("c", &circle_text(300.0, 0.0), ProfileKind::Rail, MM, 0.0).unwrap();
        let (z, _, _) = p.eval(5.0 * MM).unwrap();
        let want = -(300.0 - (300.0f64 * 300.0 - 25.0).sqrt()) * MM;
        assert!((z - want).abs() < 1e-12, "{z} vs {want}");
        for y in [-10.0, -3.3, 0.0, 7.7, 12.0] {
            let (_, _, d2) = p.eval(y * MM).unwrap();
            let exact = -1.0 / (300.0 * MM) / (1.0 - (y / 300.0f64).powi(2)).powf(1.5);
            assert!((d2 / exact - 1.0).abs() < 1e-4, "y = {y}: {d2} vs {exact}");
        }
    }

    /// Smoothing: with a ±2 µm disturbance the interpolating spline's curvature is far off;
    /// with λ = L⁴/h for a smoothing length L = 2 mm (h = 0.5 mm: λ = 3.2e-8 m³) the curvature
    /// error in the middle falls by more than 10×, while the profile stays within 3 µm of the
    /// circle.
    #[test]
    fn smoothing_reduces_noise_in_the_curvature() {
        let text = circle_text(300.0, 0.002);
        let raw = parse_profile("raw", &text, ProfileKind::Rail, MM, 0.0).unwrap();
        let smooth = parse_profile(
            "smooth",
            &text,
            ProfileKind::Rail,
            MM,
            (2.0 * MM).powi(4) / (0.5 * MM),
        )
        .unwrap();
        let exact = -1.0 / (300.0 * MM);
        let err = |p: &Profile| {
            (-5..=5)
                .map(|k| (p.eval(k as f64 * MM).unwrap().2 - exact).abs())
                .fold(0.0, f64::max)
        };
        let (e_raw, e_smooth) = (err(&raw), err(&smooth));
        assert!(e_smooth < 0.1 * e_raw, "raw {e_raw}, smoothed {e_smooth}");
        let dev = (-15..=15)
            .map(|k| {
                let y = k as f64;
                let want = -(300.0 - (300.0f64 * 300.0 - y * y).sqrt()) * MM;
                (smooth.z(y * MM).unwrap() - want).abs()
            })
            .fold(0.0, f64::max);
        assert!(
            dev < 3e-6,
            "largest deviation {dev} m; curvature errors {e_raw}, {e_smooth}"
        );
    }

    /// λ → ∞: the smoothing spline tends to the least-squares line.
    #[test]
    fn infinite_smoothing_is_the_regression_line() {
        // Points 1 cm apart zig-zagging by 1 cm; λ = 1 m³ smooths over (λh)^{1/4} = 0.3 m,
        // six times the data's extent, so the fit is the least-squares line.
        let pts: Vec<(f64, f64)> = (0..6)
            .map(|k| (0.01 * k as f64, 0.01 * (k % 2) as f64))
            .collect();
        let p = smoothing_spline("line", &pts, 1.0).unwrap();
        // Least squares: mean y 0.025, mean z 0.005, Sxy = 1.5e-4, Sxx = 1.75e-3.
        let (slope, icpt) = (1.5e-4 / 1.75e-3, 0.005 - 0.025 * 1.5e-4 / 1.75e-3);
        for y in [0.0, 0.025, 0.05] {
            assert!((p.z(y).unwrap() - (icpt + slope * y)).abs() < 1e-8, "{y}");
        }
    }

    #[test]
    fn simpack_blocks_units_and_errors_name_the_line() {
        let text = "header.begin\n  version = 1\nheader.end\nspline.begin\n  units.len.f = 1000.\n  point.begin\n  -2 0.1 ! c\n -1 0.02\n 0 0\n 1 0.02\n 2 0.1\n  point.end\nspline.end\n";
        let pts = parse_points(text, 1.0).unwrap();
        assert_eq!(pts.len(), 5);
        assert!((pts[0].0 + 2e-3).abs() < 1e-15 && pts[0].2 == 7);
        let err = parse_points("y z\n0 0\n1 x\n2 2\n3 3\n", 1.0)
            .unwrap_err()
            .to_string();
        assert!(err.contains("line 3") && err.contains("1 x"), "{err}");
        let raw = parse_points("0 0\n1 1\n1 2\n3 3\n", 1.0).unwrap();
        let err = check_monotone(&raw).unwrap_err().to_string();
        assert!(
            err.contains("line 3") && err.contains("strictly increasing"),
            "{err}"
        );
        let err = parse_points("0 0\n1 1\n", 1.0).unwrap_err().to_string();
        assert!(err.contains("at least 4"), "{err}");
    }

    /// A wheel file in a z-up frame with its flange at positive s is flipped and mirrored to
    /// the S1002 convention: sampling S1002 that way and reading it back gives S1002.
    #[test]
    fn a_mirrored_z_up_wheel_file_is_oriented() {
        let s = crate::s1002::s1002();
        let mut text = String::new();
        for k in 0..=1200 {
            let y = -65.0 + 125.0 * k as f64 / 1200.0;
            let f = s.z(y * MM).unwrap() / MM;
            text.push_str(&format!("{} {}\n", -y, -f));
        }
        let p = parse_profile("w", &text, ProfileKind::Wheel, MM, 0.0).unwrap();
        for y in [-50.0, -39.0, -20.0, 0.0, 30.0, 55.0] {
            let d = (p.z(y * MM).unwrap() - s.z(y * MM).unwrap()).abs();
            assert!(d < 2e-3 * MM, "y = {y}: {d}");
        }
    }
}
