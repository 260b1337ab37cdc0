//! The S1002 wheel profile (EN 13715; UIC 510-2), flange thickness 32.5 mm, from its
//! published sectionwise definition (references.md §W1.1).
//!
//! Coordinates: s \[m\] lateral from the tape (measuring) circle, positive towards the field
//! side (away from the flange); the inner (back) face of the wheel is at s = −70 mm. The
//! profile value F(s) \[m\] is the radius increase over the nominal rolling radius: the flange
//! has F up to +28 mm, the outer tread F < 0 (the tread is conical).
//!
//! Sections, as published (s and F in mm):
//! - A  (32.15796 … 60):           F = 1.364323640 − 0.066666667 s (1:15)
//! - B  (−26 … 32.15796):          F = Σ b_k s^k, a degree-8 polynomial
//! - C  (−35 … −26):               F = Σ c_k s^k, a degree-7 polynomial
//! - D  (−38.426669071 … −35):     F = 16.446 − √(13² − (s + 26.210665)²)
//! - E  (−39.764473993 … −38.426669071): F = −93.576667419 − 2.747477419 s (the 70° flank)
//! - F  (−49.662510381 … −39.764473993): F = 8.834924130 + √(20² − (s + 58.558326413)²)
//! - G  (−62.764705882 … −49.662510381): F = 16 + √(12² − (s + 55)²) (the flange top, 28 mm)
//! - H  (−70 … −62.764705882):     F = 9.519259302 + √(20.5² − (s + 49.5)²) (flange back)

use crate::profile::{Profile, Segment};

/// Distance from the wheel's inner (back) face to the tape circle \[m\] (EN 13715: 70 mm).
pub const TAPE_CIRCLE_FROM_BACK: f64 = 0.070;

/// Nominal flange height above the tape circle \[m\] (28 mm).
pub const FLANGE_HEIGHT: f64 = 0.028;

/// Nominal flange thickness \[m\], measured 10 mm above the tape circle from the back face.
pub const FLANGE_THICKNESS: f64 = 0.0325;

const MM: f64 = 1e-3;

/// Section B's coefficients b_0 … b_8 (mm units), signs included.
const B: [f64; 9] = [
    0.0,
    -3.358537058e-02,
    1.565681624e-03,
    -2.810427944e-05,
    5.844240864e-08,
    -1.562379023e-08,
    5.309217349e-15,
    -5.957839843e-12,
    2.646656573e-13,
];

/// Section C's coefficients c_0 … c_7 (mm units), signs included.
const C: [f64; 8] = [
    -4.320221063e+03,
    -1.038384026e+03,
    -1.065501873e+02,
    -6.051367875,
    -2.054332446e-01,
    -4.169739389e-03,
    -4.687195829e-05,
    -2.252755540e-07,
];

/// Polynomial coefficients in mm units to SI: F\[m\] = Σ c_k 10^{3k−3} s\[m\]^k.
fn si_poly(c: &[f64]) -> Vec<f64> {
    c.iter()
        .enumerate()
        .map(|(k, v)| v * 10f64.powi(3 * k as i32 - 3))
        .collect()
}

fn arc(y0: f64, y1: f64, a: f64, r: f64, c: f64, upper: bool) -> Segment {
    Segment::Arc {
        y0: y0 * MM,
        y1: y1 * MM,
        yc: -c * MM,
        zc: a * MM,
        r: r * MM,
        upper,
    }
}

/// The S1002 profile F(s) on s ∈ \[−70, 60\] mm (in metres).
pub fn s1002() -> Profile {
    let bp = [
        -70.0,
        -62.764705882,
        -49.662510381,
        -39.764473993,
        -38.426669071,
        -35.0,
        -26.0,
        32.15796,
        60.0,
    ];
    let segments = vec![
        arc(bp[0], bp[1], 9.519259302, 20.5, 49.5, true),
        arc(bp[1], bp[2], 16.0, 12.0, 55.0, true),
        arc(bp[2], bp[3], 8.834924130, 20.0, 58.558326413, true),
        Segment::Line {
            y0: bp[3] * MM,
            y1: bp[4] * MM,
            z0: (-93.576667419 - 2.747477419 * bp[3]) * MM,
            slope: -2.747477419,
        },
        arc(bp[4], bp[5], 16.446, 13.0, 26.210665, false),
        Segment::Polynomial {
            y0: bp[5] * MM,
            y1: bp[6] * MM,
            coeffs: si_poly(&C),
        },
        Segment::Polynomial {
            y0: bp[6] * MM,
            y1: bp[7] * MM,
            coeffs: si_poly(&B),
        },
        Segment::Line {
            y0: bp[7] * MM,
            y1: bp[8] * MM,
            z0: (1.364323640 - 0.066666667 * bp[7]) * MM,
            slope: -0.066666667,
        },
    ];
    Profile::new("S1002", segments).expect("the published S1002 sections are ordered and joined")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn solve(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
        for _ in 0..200 {
            let m = 0.5 * (a + b);
            if f(a) * f(m) <= 0.0 {
                b = m;
            } else {
                a = m;
            }
        }
        0.5 * (a + b)
    }

    /// Value and slope are continuous at every breakpoint. Tolerances: the published
    /// coefficients carry 10 significant digits; the largest mismatches are at the ends of
    /// the polynomial sections (measured 1.2e-4 mm in value and 7.7e-6 in slope at
    /// s = −35 mm, 3.7e-5 mm and 3.2e-6 at s = −26 mm); elsewhere they are below 1e-7 mm.
    #[test]
    fn value_and_slope_are_continuous_at_every_breakpoint() {
        let p = s1002();
        let jumps = p.jumps();
        assert_eq!(jumps.len(), 7);
        for j in &jumps {
            assert!(
                j.value.abs() < 2e-4 * MM,
                "value jump {} m at {}",
                j.value,
                j.y
            );
            assert!(j.slope.abs() < 1e-5, "slope jump {} at {}", j.slope, j.y);
        }
        // The arc/line joins are exact to the published digits.
        for j in jumps.iter().filter(|j| j.y < -35.5 * MM || j.y > 0.0) {
            assert!(
                j.value.abs() < 1e-7 * MM,
                "value jump {} m at {}",
                j.value,
                j.y
            );
            assert!(j.slope.abs() < 1e-8, "slope jump {} at {}", j.slope, j.y);
        }
    }

    /// Key dimensions of EN 13715's S1002 with flange thickness 32.5 mm: flange height
    /// 28 mm, flange thickness 32.5 mm at 10 mm above the tape circle measured from the back
    /// face (s = −70 mm), qR = 10.8 mm (horizontal distance between the flange-thickness
    /// point and the flange point 2 mm below the flange top), flank angle 70°. The published
    /// values are rounded to 0.1 mm and 1°, which sets the tolerances.
    #[test]
    fn published_key_dimensions() {
        let p = s1002();
        let f = |s: f64| p.z(s).unwrap();
        let top = (-600..=-500)
            .map(|k| f(k as f64 * 0.1 * MM))
            .fold(f64::MIN, f64::max);
        assert!((top - FLANGE_HEIGHT).abs() < 1e-9, "flange height {top}");
        let front = solve(|s| f(s) - 10.0 * MM, -45.0 * MM, -30.0 * MM);
        let thickness = front + TAPE_CIRCLE_FROM_BACK;
        assert!(
            (thickness - FLANGE_THICKNESS).abs() < 0.05 * MM,
            "flange thickness {thickness}"
        );
        let high = solve(|s| f(s) - 26.0 * MM, -54.0 * MM, -40.0 * MM);
        let qr = front - high;
        assert!((qr - 10.8 * MM).abs() < 0.05 * MM, "qR {qr}");
        let (_, slope, _) = p.eval(-39.0 * MM).unwrap();
        let angle = (-slope).atan().to_degrees();
        assert!((angle - 70.0).abs() < 1e-6, "flank angle {angle}");
        // At the tape circle F = 0 by definition.
        assert!(f(0.0).abs() < 1e-15);
    }
}
