//! Piecewise profiles z(y): lines, circular arcs and polynomials between breakpoints
//! (references.md §W1).
//!
//! A profile is a function z(y) \[m\] of the lateral coordinate y \[m\] on a closed interval,
//! made of segments that join at breakpoints. What z means (rail height upwards, wheel
//! radius increase) is up to the profile's owner ([`crate::s1002()`], [`crate::rail_60e1()`]).

use crate::error::WheelRailError;

/// One segment of a profile on [`y0`, `y1`].
#[derive(Debug, Clone, PartialEq)]
pub enum Segment {
    /// z = z0 + slope · (y − y0).
    Line {
        y0: f64,
        y1: f64,
        z0: f64,
        slope: f64,
    },
    /// The upper (`upper = true`: z = zc + √(r² − (y − yc)²)) or lower half of the circle of
    /// radius `r` about (yc, zc).
    Arc {
        y0: f64,
        y1: f64,
        yc: f64,
        zc: f64,
        r: f64,
        upper: bool,
    },
    /// z = Σ c\[k\] · y^k (absolute y).
    Polynomial { y0: f64, y1: f64, coeffs: Vec<f64> },
    /// z = a + b t + c t² + d t³ with t = y − y0 (spline pieces).
    Cubic {
        y0: f64,
        y1: f64,
        a: f64,
        b: f64,
        c: f64,
        d: f64,
    },
}

impl Segment {
    /// The segment's interval (y0, y1).
    pub fn range(&self) -> (f64, f64) {
        match *self {
            Segment::Line { y0, y1, .. }
            | Segment::Arc { y0, y1, .. }
            | Segment::Cubic { y0, y1, .. } => (y0, y1),
            Segment::Polynomial { y0, y1, .. } => (y0, y1),
        }
    }

    /// z, dz/dy and d²z/dy² at `y` (no range check; arcs are evaluated on their circle,
    /// with the argument of the root clamped at zero at the vertical tangent).
    pub fn eval(&self, y: f64) -> (f64, f64, f64) {
        match self {
            Segment::Line { y0, z0, slope, .. } => (z0 + slope * (y - y0), *slope, 0.0),
            Segment::Arc {
                yc, zc, r, upper, ..
            } => {
                let u = y - yc;
                let w = (r * r - u * u).max(1e-300).sqrt();
                let sign = if *upper { 1.0 } else { -1.0 };
                let z = zc + sign * w;
                let dz = -sign * u / w;
                let d2z = -sign * r * r / (w * w * w);
                (z, dz, d2z)
            }
            Segment::Polynomial { coeffs, .. } => {
                let (mut z, mut dz, mut d2z) = (0.0, 0.0, 0.0);
                for c in coeffs.iter().rev() {
                    d2z = d2z * y + 2.0 * dz;
                    dz = dz * y + z;
                    z = z * y + c;
                }
                (z, dz, d2z)
            }
            Segment::Cubic { y0, a, b, c, d, .. } => {
                let t = y - y0;
                (
                    a + t * (b + t * (c + t * d)),
                    b + t * (2.0 * c + 3.0 * d * t),
                    2.0 * c + 6.0 * d * t,
                )
            }
        }
    }
}

/// A validated piecewise profile: segments ordered in y and joined end to end.
#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    name: String,
    segments: Vec<Segment>,
}

/// A value or slope jump of a profile at one breakpoint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jump {
    /// The breakpoint \[m\].
    pub y: f64,
    /// z(right) − z(left) \[m\].
    pub value: f64,
    /// z′(right) − z′(left) \[-\].
    pub slope: f64,
}

impl Profile {
    /// A profile from its segments, which must be non-empty, each with y0 < y1, finite, and
    /// joined end to end (y1 of one = y0 of the next within 1e-12 m).
    pub fn new(name: impl Into<String>, segments: Vec<Segment>) -> Result<Self, WheelRailError> {
        let name = name.into();
        if segments.is_empty() {
            return Err(WheelRailError::InvalidProfile(format!(
                "profile `{name}` has no segments"
            )));
        }
        for (i, s) in segments.iter().enumerate() {
            let (a, b) = s.range();
            if !(a.is_finite() && b.is_finite() && a < b) {
                return Err(WheelRailError::InvalidProfile(format!(
                    "profile `{name}`, segment {i}: interval [{a}, {b}] must be finite with y0 < y1"
                )));
            }
            if i > 0 {
                let prev = segments[i - 1].range().1;
                if (prev - a).abs() > 1e-12 {
                    return Err(WheelRailError::InvalidProfile(format!(
                        "profile `{name}`, segment {i} starts at y = {a} m but segment {} ends at y = {prev} m",
                        i - 1
                    )));
                }
            }
        }
        Ok(Profile { name, segments })
    }

    /// The profile's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The segments.
    pub fn segments(&self) -> &[Segment] {
        &self.segments
    }

    /// The lateral extent (y_min, y_max) \[m\].
    pub fn y_range(&self) -> (f64, f64) {
        (
            self.segments[0].range().0,
            self.segments[self.segments.len() - 1].range().1,
        )
    }

    /// The interior breakpoints \[m\].
    pub fn breakpoints(&self) -> Vec<f64> {
        self.segments[1..].iter().map(|s| s.range().0).collect()
    }

    fn segment_at(&self, y: f64) -> &Segment {
        let i = self.segments.partition_point(|s| s.range().1 < y);
        &self.segments[i.min(self.segments.len() - 1)]
    }

    /// z, dz/dy, d²z/dy² at `y`, or `None` outside the profile.
    pub fn eval(&self, y: f64) -> Option<(f64, f64, f64)> {
        let (lo, hi) = self.y_range();
        // Rounding of computed end points (lo + (hi − lo)·k/n) may step past an end by a few
        // ulps: such points are the end.
        let tol = 1e-12 * (hi - lo).abs().max(1e-3);
        if !(y >= lo - tol && y <= hi + tol) {
            return None;
        }
        let y = y.clamp(lo, hi);
        Some(self.segment_at(y).eval(y))
    }

    /// z(y), or `None` outside the profile.
    pub fn z(&self, y: f64) -> Option<f64> {
        self.eval(y).map(|e| e.0)
    }

    /// The value and slope jumps at every interior breakpoint (both sides evaluated with
    /// their own segment's formula).
    pub fn jumps(&self) -> Vec<Jump> {
        self.segments
            .windows(2)
            .map(|w| {
                let y = w[1].range().0;
                let (zl, dl, _) = w[0].eval(y);
                let (zr, dr, _) = w[1].eval(y);
                Jump {
                    y,
                    value: zr - zl,
                    slope: dr - dl,
                }
            })
            .collect()
    }

    /// The profile mirrored about y = 0: z_m(y) = z(−y).
    pub fn mirrored(&self) -> Profile {
        let segments = self
            .segments
            .iter()
            .rev()
            .map(|s| match s {
                Segment::Line { y0, y1, z0, slope } => Segment::Line {
                    y0: -y1,
                    y1: -y0,
                    z0: z0 + slope * (y1 - y0),
                    slope: -slope,
                },
                Segment::Arc {
                    y0,
                    y1,
                    yc,
                    zc,
                    r,
                    upper,
                } => Segment::Arc {
                    y0: -y1,
                    y1: -y0,
                    yc: -yc,
                    zc: *zc,
                    r: *r,
                    upper: *upper,
                },
                Segment::Polynomial { y0, y1, coeffs } => Segment::Polynomial {
                    y0: -y1,
                    y1: -y0,
                    coeffs: coeffs
                        .iter()
                        .enumerate()
                        .map(|(k, c)| if k % 2 == 1 { -c } else { *c })
                        .collect(),
                },
                Segment::Cubic { y0, y1, a, b, c, d } => {
                    // Re-expand about the new left end −y1: t' = y' + y1, z(−y') with
                    // t = −y' − y0 = h − t', h = y1 − y0.
                    let h = y1 - y0;
                    let (z, dz, d2z) = (
                        a + h * (b + h * (c + h * d)),
                        b + h * (2.0 * c + 3.0 * d * h),
                        2.0 * c + 6.0 * d * h,
                    );
                    Segment::Cubic {
                        y0: -y1,
                        y1: -y0,
                        a: z,
                        b: -dz,
                        c: 0.5 * d2z,
                        d: -d,
                    }
                }
            })
            .collect();
        Profile {
            name: self.name.clone(),
            segments,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polynomial_and_its_derivatives_match_closed_form() {
        // z = 1 + 2y + 3y² + 4y³ at y = 0.5: 1 + 1 + 0.75 + 0.5 = 3.25;
        // z' = 2 + 6y + 12y² = 8; z'' = 6 + 24y = 18.
        let s = Segment::Polynomial {
            y0: 0.0,
            y1: 1.0,
            coeffs: vec![1.0, 2.0, 3.0, 4.0],
        };
        let (z, dz, d2z) = s.eval(0.5);
        assert!((z - 3.25).abs() < 1e-15 && (dz - 8.0).abs() < 1e-15 && (d2z - 18.0).abs() < 1e-14);
    }

    #[test]
    fn arc_slope_and_curvature_are_those_of_the_circle() {
        // Lower half of the unit circle about the origin at y = 0.6: z = −0.8,
        // z' = 0.6/0.8 = 0.75, z'' = 1/0.8³ = 1.953125.
        let s = Segment::Arc {
            y0: -1.0,
            y1: 1.0,
            yc: 0.0,
            zc: 0.0,
            r: 1.0,
            upper: false,
        };
        let (z, dz, d2z) = s.eval(0.6);
        assert!((z + 0.8).abs() < 1e-15);
        assert!((dz - 0.75).abs() < 1e-14);
        assert!((d2z - 1.953125).abs() < 1e-12);
    }

    #[test]
    fn mirroring_reflects_every_segment_kind() {
        let p = Profile::new(
            "test",
            vec![
                Segment::Line {
                    y0: -2.0,
                    y1: -1.0,
                    z0: 0.0,
                    slope: 0.5,
                },
                Segment::Polynomial {
                    y0: -1.0,
                    y1: 0.5,
                    coeffs: vec![0.3, -0.2, 0.1, 0.05],
                },
                Segment::Cubic {
                    y0: 0.5,
                    y1: 1.0,
                    a: 0.2,
                    b: 0.1,
                    c: -0.3,
                    d: 0.7,
                },
                Segment::Arc {
                    y0: 1.0,
                    y1: 1.5,
                    yc: 1.2,
                    zc: 3.0,
                    r: 2.0,
                    upper: false,
                },
            ],
        )
        .unwrap();
        let m = p.mirrored();
        for k in 0..=70 {
            // Off the breakpoints (this test profile is not continuous there).
            let y = -2.0 + 3.5 * (k as f64 + 0.5) / 71.0;
            let (z, dz, d2z) = p.eval(y).unwrap();
            let (zm, dzm, d2zm) = m.eval(-y).unwrap();
            assert!((z - zm).abs() < 1e-12, "y = {y}");
            assert!((dz + dzm).abs() < 1e-12, "y = {y}");
            assert!((d2z - d2zm).abs() < 1e-9, "y = {y}");
        }
    }

    #[test]
    fn disjoint_segments_are_refused_with_their_positions() {
        let err = Profile::new(
            "gap",
            vec![
                Segment::Line {
                    y0: 0.0,
                    y1: 1.0,
                    z0: 0.0,
                    slope: 0.0,
                },
                Segment::Line {
                    y0: 1.5,
                    y1: 2.0,
                    z0: 0.0,
                    slope: 0.0,
                },
            ],
        )
        .unwrap_err()
        .to_string();
        assert!(err.contains("segment 1 starts at y = 1.5"), "{err}");
    }
}
