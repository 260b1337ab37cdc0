//! The undeformed gap h(x, t) of one contact candidate in its contact plane
//! (references.md §W3.1).
//!
//! The contact plane passes through the candidate's contact point and is tangent to both
//! surfaces there (inclined by the contact angle γ). Across the track (t, in the plane,
//! towards the field side) the gap is the distance between the two profiles measured along
//! the plane's normal: both placed profiles are rotated by −γ about the contact point and
//! subtracted. Along the track (x) the rail is straight and the wheel is a body of
//! revolution: at lateral position t its rolling radius r(t) = r₀ + F(s(t)) varies across the
//! patch, and its surface recedes by r − √(r² − x²) in the radial direction, which makes the
//! angle γ − φ with the plane's normal (φ the roll of the wheel's side). Hence
//! h(x, t) = h(0, t) + (r(t) − √(r(t)² − x²)) cos(γ − φ).

use crate::contact_point::ContactCandidate;
use crate::placed::PlacedProfile;
use crate::wheelset::{Wheelset, WheelsetContact};

/// Which wheel of the wheelset.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// The right wheel (towards positive Y).
    Right,
    /// The left wheel, described mirrored to the right.
    Left,
}

/// A contact plane with the two profiles expressed in it.
#[derive(Debug, Clone)]
pub struct ContactPlane<'a> {
    wheel: PlacedProfile<'a>,
    rail: PlacedProfile<'a>,
    /// Contact angle γ of the plane \[rad\].
    pub angle: f64,
    /// The plane's origin (the candidate's contact point) in the side's track frame (Y, Z).
    pub origin: (f64, f64),
    /// Roll of this wheel in its (mirrored) frame \[rad\].
    pub roll: f64,
    wheel_radius: f64,
    profile_wheel: &'a crate::profile::Profile,
}

fn into_plane<'a>(p: PlacedProfile<'a>, angle: f64, origin: (f64, f64)) -> PlacedProfile<'a> {
    let (s, c) = (-angle).sin_cos();
    let (dy, dz) = (p.offset.0 - origin.0, p.offset.1 - origin.1);
    PlacedProfile {
        profile: p.profile,
        sign: p.sign,
        angle: p.angle - angle,
        offset: (c * dy - s * dz, s * dy + c * dz),
    }
}

impl<'a> ContactPlane<'a> {
    /// The plane of `candidate` of the `side` wheel of the rigid contact `contact`.
    pub fn new(
        wheelset: &'a Wheelset,
        contact: &WheelsetContact,
        side: Side,
        candidate: &ContactCandidate,
    ) -> Self {
        let (y_ws, roll) = match side {
            Side::Right => (contact.lateral_shift, contact.roll),
            Side::Left => (-contact.lateral_shift, -contact.roll),
        };
        let wheel = wheelset.right_wheel(y_ws, roll, contact.axle_height);
        let rail = wheelset.right_rail();
        let angle = candidate.contact_angle();
        let origin = (candidate.y, candidate.z);
        ContactPlane {
            wheel: into_plane(wheel, angle, origin),
            rail: into_plane(rail, angle, origin),
            angle,
            origin,
            roll,
            wheel_radius: wheelset.params().wheel_radius,
            profile_wheel: wheelset.wheel(),
        }
    }

    /// Gap across the track at x = 0 \[m\], or `None` where a profile ends.
    pub fn cross_gap(&self, t: f64) -> Option<f64> {
        Some(self.wheel.at(t)?.z - self.rail.at(t)?.z)
    }

    /// Rolling radius of the wheel at lateral plane coordinate `t` \[m\].
    pub fn rolling_radius(&self, t: f64) -> Option<f64> {
        let s = self.wheel.at(t)?.local;
        Some(self.wheel_radius + self.profile_wheel.z(s)?)
    }

    /// The undeformed gap h(x, t) \[m\] (+∞ outside the profiles).
    pub fn gap(&self, x: f64, t: f64) -> f64 {
        let (Some(h0), Some(r)) = (self.cross_gap(t), self.rolling_radius(t)) else {
            return f64::INFINITY;
        };
        if x.abs() >= r {
            return f64::INFINITY;
        }
        h0 + (r - (r * r - x * x).sqrt()) * (self.angle - self.roll).cos()
    }

    /// Map a plane point (t along the plane, n along its normal) to the side's track frame.
    pub fn to_track(&self, t: f64, n: f64) -> (f64, f64) {
        let (s, c) = self.angle.sin_cos();
        (self.origin.0 + c * t - s * n, self.origin.1 + s * t + c * n)
    }
}
