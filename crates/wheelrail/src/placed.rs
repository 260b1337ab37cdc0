//! A profile placed in the track cross-section: rotated by an angle and translated
//! (references.md §W2.1).
//!
//! A profile point (y, σ·z(y)) (σ = ±1 picks which way the profile's values point) maps to
//! (Y, Z) = R(θ)·(y, σ z) + (t_y, t_z) in the track frame (Y lateral, Z upwards). The placed
//! curve is evaluated as a function Z(Y): the profile parameter y of a given Y is found by
//! bisection, which needs Y(y) monotone (dY/dy = cos θ − σ sin θ z′(y) ≥ 0: true for the
//! profiles here and cant or roll angles below 1:20 on flanks no steeper than 1:20).

use crate::profile::Profile;

/// A profile rotated and translated into the track frame.
#[derive(Debug, Clone)]
pub struct PlacedProfile<'a> {
    /// The profile.
    pub profile: &'a Profile,
    /// σ: +1 keeps the profile's z, −1 flips it (a wheel profile of radius increase F has its
    /// surface at −F).
    pub sign: f64,
    /// The rotation angle θ \[rad\], counter-clockwise (Y towards Z).
    pub angle: f64,
    /// The translation (t_y, t_z) \[m\].
    pub offset: (f64, f64),
}

/// A point of a placed profile.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlacedPoint {
    /// The profile parameter y \[m\] (the profile's own lateral coordinate).
    pub local: f64,
    /// Height Z \[m\] in the track frame.
    pub z: f64,
    /// Slope dZ/dY in the track frame.
    pub slope: f64,
    /// Curvature of the curve, d²Z/dY² / (1 + (dZ/dY)²)^{3/2} \[1/m\] (positive when convex
    /// from below, i.e. when the curve bends upwards).
    pub curvature: f64,
}

impl<'a> PlacedProfile<'a> {
    /// Map a profile parameter to the track frame: (Y, Z).
    pub fn map(&self, y: f64) -> Option<(f64, f64)> {
        let z = self.sign * self.profile.z(y)?;
        let (s, c) = self.angle.sin_cos();
        Some((c * y - s * z + self.offset.0, s * y + c * z + self.offset.1))
    }

    /// The lateral extent (Y at the profile's ends).
    pub fn y_range(&self) -> (f64, f64) {
        let (lo, hi) = self.profile.y_range();
        let a = self.map(lo).expect("in range").0;
        let b = self.map(hi).expect("in range").0;
        (a.min(b), a.max(b))
    }

    /// The point of the placed curve at track coordinate `y_track`, or `None` outside it.
    pub fn at(&self, y_track: f64) -> Option<PlacedPoint> {
        let (lo, hi) = self.profile.y_range();
        let ylo = self.map(lo)?.0;
        let yhi = self.map(hi)?.0;
        if !(y_track >= ylo && y_track <= yhi) {
            return None;
        }
        // Safeguarded Newton on Y(y) = y_track (dY/dy = cos θ − σ sin θ z′(y) > 0): the
        // bracket [a, b] always holds the root; a Newton step is taken when it stays inside
        // and shrinks the step at least by half, a bisection otherwise; stops at a step below
        // 1e-15 m or a bracket below 1e-14 m.
        let (s, c) = self.angle.sin_cos();
        let (mut a, mut b) = (lo, hi);
        let mut y = if yhi > ylo {
            (lo + (hi - lo) * (y_track - ylo) / (yhi - ylo)).clamp(lo, hi)
        } else {
            0.5 * (lo + hi)
        };
        let mut step_old = hi - lo;
        for _ in 0..200 {
            let (z, dz, _) = self.profile.eval(y)?;
            let f = c * y - s * self.sign * z + self.offset.0 - y_track;
            if f < 0.0 {
                a = y;
            } else {
                b = y;
            }
            let slope = c - s * self.sign * dz;
            let newton = y - f / slope;
            let step = if slope > 0.0
                && newton >= a
                && newton <= b
                && 2.0 * f.abs() <= (step_old * slope).abs()
            {
                let d = y - newton;
                y = newton;
                d
            } else {
                y = 0.5 * (a + b);
                0.5 * (b - a)
            };
            step_old = step;
            if step.abs() < 1e-15 || b - a < 1e-14 {
                break;
            }
        }
        Some(self.point_at_local(y))
    }

    /// The point at profile parameter `y` (inside the profile).
    pub fn point_at_local(&self, y: f64) -> PlacedPoint {
        let (z, dz, d2z) = self.profile.eval(y).expect("inside the profile");
        let (z, dz, d2z) = (self.sign * z, self.sign * dz, self.sign * d2z);
        let (s, c) = self.angle.sin_cos();
        let z_track = s * y + c * z + self.offset.1;
        // Tangent (1, z′) rotated: (c − s z′, s + c z′).
        let ty = c - s * dz;
        let tz = s + c * dz;
        let slope = tz / ty;
        // Curvature is invariant under rotation: z″ / (1 + z′²)^{3/2}.
        let curvature = d2z / (1.0 + dz * dz).powf(1.5);
        PlacedPoint {
            local: y,
            z: z_track,
            slope,
            curvature,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::profile::Segment;

    #[test]
    fn a_rotated_line_has_the_rotated_slope_and_the_inverse_finds_its_parameter() {
        let p = Profile::new(
            "line",
            vec![Segment::Line {
                y0: -1.0,
                y1: 1.0,
                z0: -0.2,
                slope: 0.2,
            }],
        )
        .unwrap();
        let theta: f64 = 0.1;
        let placed = PlacedProfile {
            profile: &p,
            sign: 1.0,
            angle: theta,
            offset: (0.3, -0.1),
        };
        // Slope of the rotated line: tan(atan 0.2 + θ).
        let want = (0.2f64.atan() + theta).tan();
        let (y, _) = placed.map(0.25).unwrap();
        let pt = placed.at(y).unwrap();
        assert!((pt.local - 0.25).abs() < 1e-12);
        assert!((pt.slope - want).abs() < 1e-12);
        assert_eq!(pt.curvature, 0.0);
    }
}
