//! A wheelset on a straight track: track gauge, rail inclination, back-to-back distance,
//! nominal rolling radius; the rigid contact of both wheels at a lateral shift, with the
//! roll angle that keeps both wheels on their rails (references.md §W2).
//!
//! Track frame: Y lateral from the track centre line, positive towards the right rail; Z
//! upwards, Z = 0 at the top of the rails. The right rail is the rail profile rotated by the
//! inclination (its head tilted towards the track centre) and placed so that its gauge point
//! (the point of the gauge face `gauge_depth` below the top) is at Y = gauge/2. The right
//! wheel's tape circle is at Y = y_ws + back_to_back/2 + tape_offset, its flange towards the
//! track centre. The left side is the mirror image: the left pair at (y_ws, φ) is the right
//! pair at (−y_ws, −φ) reflected in Y = 0.

use crate::contact_point::{ContactCandidate, search};
use crate::error::{WheelRailError, in_range};
use crate::placed::PlacedProfile;
use crate::profile::Profile;

/// The wheelset and track dimensions. Lengths in metres, the inclination as the tangent of
/// the cant angle (1:40 → 0.025).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelsetParams {
    /// Track gauge \[m\] (standard 1.435).
    pub gauge: f64,
    /// Rail inclination (tangent of the cant angle): 1/20, 1/40 or 0.
    pub inclination: f64,
    /// Distance between the wheels' inner faces \[m\] (standard 1.360).
    pub back_to_back: f64,
    /// Distance from a wheel's inner face to its tape circle \[m\] (S1002: 0.070).
    pub tape_offset: f64,
    /// Nominal rolling radius (at the tape circle) \[m\].
    pub wheel_radius: f64,
    /// Depth below the rail top of the gauge point \[m\] (EN 13848-1: 0.014).
    pub gauge_depth: f64,
}

impl Default for WheelsetParams {
    fn default() -> Self {
        WheelsetParams {
            gauge: 1.435,
            inclination: 1.0 / 40.0,
            back_to_back: 1.360,
            tape_offset: 0.070,
            wheel_radius: 0.46,
            gauge_depth: 0.014,
        }
    }
}

impl WheelsetParams {
    /// Range checks; the error names the key, its value and the allowed range.
    pub fn validate(&self) -> Result<(), WheelRailError> {
        in_range("gauge", self.gauge, 0.6, 2.0, "must lie in [0.6, 2.0] m")?;
        in_range(
            "inclination",
            self.inclination,
            0.0,
            0.05,
            "must lie in [0, 1/20] (tangent of the cant angle)",
        )?;
        in_range(
            "back_to_back",
            self.back_to_back,
            0.5,
            1.9,
            "must lie in [0.5, 1.9] m",
        )?;
        in_range(
            "tape_offset",
            self.tape_offset,
            0.0,
            0.2,
            "must lie in [0, 0.2] m",
        )?;
        in_range(
            "wheel_radius",
            self.wheel_radius,
            0.1,
            1.0,
            "must lie in [0.1, 1.0] m",
        )?;
        in_range(
            "gauge_depth",
            self.gauge_depth,
            0.0,
            0.03,
            "must lie in [0, 0.03] m",
        )?;
        Ok(())
    }
}

/// How the wheelset's roll angle is set.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Roll {
    /// The roll that keeps both wheels in contact (rigid wheelset resting on both rails).
    Equilibrium,
    /// A prescribed roll angle \[rad\] (counter-clockwise: the right wheel rises); the
    /// wheelset is lowered until its first contact.
    Fixed(f64),
}

/// The rigid contact of one wheel on its rail.
#[derive(Debug, Clone, PartialEq)]
pub struct WheelContact {
    /// Every local minimum of the vertical wheel–rail distance, closest first, with `gap`
    /// measured from the lowered wheelset (the first one has gap 0 when this wheel touches).
    /// Positions are in the track frame of this wheel's side mirrored to the right (Y > 0
    /// towards the field side; contact angles positive towards the flange).
    pub candidates: Vec<ContactCandidate>,
    /// Rolling radius at each candidate \[m\].
    pub radii: Vec<f64>,
}

impl WheelContact {
    /// The contact point (smallest gap).
    pub fn principal(&self) -> &ContactCandidate {
        &self.candidates[0]
    }

    /// Rolling radius at the contact point \[m\].
    pub fn rolling_radius(&self) -> f64 {
        self.radii[0]
    }
}

/// The rigid contact of the wheelset at one lateral shift.
#[derive(Debug, Clone, PartialEq)]
pub struct WheelsetContact {
    /// Lateral shift y_ws \[m\].
    pub lateral_shift: f64,
    /// Roll angle φ \[rad\].
    pub roll: f64,
    /// Height of the axle above its nominal height r₀ \[m\] (negative: lowered).
    pub axle_height: f64,
    /// The right wheel (y_ws > 0 moves the wheelset towards it).
    pub right: WheelContact,
    /// The left wheel, mirrored to the right.
    pub left: WheelContact,
}

impl WheelsetContact {
    /// Rolling radius difference Δr = r_right − r_left \[m\].
    pub fn delta_r(&self) -> f64 {
        self.right.rolling_radius() - self.left.rolling_radius()
    }
}

/// A wheelset with its wheel and rail profiles.
#[derive(Debug, Clone)]
pub struct Wheelset {
    wheel: Profile,
    rail: Profile,
    params: WheelsetParams,
    rail_offset: (f64, f64),
}

impl Wheelset {
    /// A wheelset: `wheel` is a radius-increase profile F(s) (s from the tape circle,
    /// positive away from the flange), `rail` a height profile z(y) (y from the head centre,
    /// z = 0 at the top; a right-hand rail: its gauge side at negative y).
    pub fn new(
        wheel: Profile,
        rail: Profile,
        params: WheelsetParams,
    ) -> Result<Self, WheelRailError> {
        params.validate()?;
        let mut ws = Wheelset {
            wheel,
            rail,
            params,
            rail_offset: (0.0, 0.0),
        };
        ws.rail_offset = ws.place_rail()?;
        Ok(ws)
    }

    /// The dimensions.
    pub fn params(&self) -> &WheelsetParams {
        &self.params
    }

    /// The wheel profile.
    pub fn wheel(&self) -> &Profile {
        &self.wheel
    }

    /// The rail profile.
    pub fn rail(&self) -> &Profile {
        &self.rail
    }

    fn cant(&self) -> f64 {
        self.params.inclination.atan()
    }

    /// The right rail placed in the track frame.
    pub fn right_rail(&self) -> PlacedProfile<'_> {
        PlacedProfile {
            profile: &self.rail,
            sign: 1.0,
            angle: self.cant(),
            offset: self.rail_offset,
        }
    }

    /// The right wheel placed in the track frame for lateral shift `y_ws`, roll `roll` and
    /// axle height `axle` (above the nominal r₀).
    pub fn right_wheel(&self, y_ws: f64, roll: f64, axle: f64) -> PlacedProfile<'_> {
        let (s, c) = roll.sin_cos();
        let p = &self.params;
        let y_tape = 0.5 * p.back_to_back + p.tape_offset;
        let r0 = p.wheel_radius;
        PlacedProfile {
            profile: &self.wheel,
            sign: -1.0,
            angle: roll,
            offset: (c * y_tape + s * r0 + y_ws, s * y_tape - c * r0 + r0 + axle),
        }
    }

    /// Offset of the right rail: its top at Z = 0, its gauge point at Y = gauge/2.
    fn place_rail(&self) -> Result<(f64, f64), WheelRailError> {
        let placed = PlacedProfile {
            profile: &self.rail,
            sign: 1.0,
            angle: self.cant(),
            offset: (0.0, 0.0),
        };
        let (lo, hi) = self.rail.y_range();
        let map = |y: f64| -> Result<(f64, f64), WheelRailError> {
            placed.map(y.clamp(lo, hi)).ok_or_else(|| {
                WheelRailError::InvalidProfile(format!(
                    "rail `{}`: no value at y = {y} m",
                    self.rail.name()
                ))
            })
        };
        // Highest point: sample then refine.
        let n = 4000;
        let mut best = (lo, f64::NEG_INFINITY);
        for i in 0..=n {
            let y = lo + (hi - lo) * i as f64 / n as f64;
            let z = map(y)?.1;
            if z > best.1 {
                best = (y, z);
            }
        }
        let step = (hi - lo) / n as f64;
        let mut a = (best.0 - step).max(lo);
        let mut b = (best.0 + step).min(hi);
        for _ in 0..100 {
            let m1 = a + (b - a) / 3.0;
            let m2 = b - (b - a) / 3.0;
            if map(m1)?.1 < map(m2)?.1 {
                a = m1;
            } else {
                b = m2;
            }
        }
        let top_local = 0.5 * (a + b);
        let z_top = map(top_local)?.1;
        let target = z_top - self.params.gauge_depth;
        if map(lo)?.1 > target {
            return Err(WheelRailError::InvalidProfile(format!(
                "rail `{}` does not reach {} m below its top on the gauge side (needed for the gauge point)",
                self.rail.name(),
                self.params.gauge_depth
            )));
        }
        // Gauge point: on the gauge side (local y < top), Z rises towards the top.
        let (mut a, mut b) = (lo, top_local);
        for _ in 0..200 {
            let m = 0.5 * (a + b);
            if map(m)?.1 < target {
                a = m;
            } else {
                b = m;
            }
        }
        let y_gauge = map(0.5 * (a + b))?.0;
        Ok((0.5 * self.params.gauge - y_gauge, -z_top))
    }

    /// Candidates of the right wheel at (y_ws, roll) with the axle at nominal height.
    fn right_side(&self, y_ws: f64, roll: f64) -> Result<Vec<ContactCandidate>, WheelRailError> {
        let wheel = self.right_wheel(y_ws, roll, 0.0);
        let rail = self.right_rail();
        let c = search(&wheel, &rail).map_err(|e| match e {
            WheelRailError::NoOverlap { .. } => WheelRailError::NoOverlap {
                lateral_shift: y_ws,
            },
            other => other,
        })?;
        if c.is_empty() {
            return Err(WheelRailError::NoOverlap {
                lateral_shift: y_ws,
            });
        }
        Ok(c)
    }

    /// The rigid contact of both wheels at lateral shift `y_ws` \[m\].
    pub fn contact(&self, y_ws: f64, roll: Roll) -> Result<WheelsetContact, WheelRailError> {
        in_range(
            "lateral_shift",
            y_ws,
            -0.05,
            0.05,
            "must lie in [-0.05, 0.05] m",
        )?;
        let sides = |phi: f64| -> Result<_, WheelRailError> {
            let r = self.right_side(y_ws, phi)?;
            let l = self.right_side(-y_ws, -phi)?;
            Ok((r, l))
        };
        let phi = match roll {
            Roll::Fixed(phi) => {
                in_range("roll", phi, -0.05, 0.05, "must lie in [-0.05, 0.05] rad")?;
                phi
            }
            Roll::Equilibrium => {
                // d(φ) = g_R − g_L ≈ d(0) + 2 y_tape φ; secant iteration.
                let d = |phi: f64| -> Result<f64, WheelRailError> {
                    let (r, l) = sides(phi)?;
                    Ok(r[0].gap - l[0].gap)
                };
                let y_tape = 0.5 * self.params.back_to_back + self.params.tape_offset;
                let mut p0 = 0.0;
                let mut d0 = d(p0)?;
                let mut p1 = -d0 / (2.0 * y_tape);
                let mut d1 = d(p1)?;
                let mut iterations = 0;
                while d1.abs() > 1e-12 {
                    iterations += 1;
                    if iterations > 50 || d1 == d0 {
                        return Err(WheelRailError::NotConverged {
                            what: "roll angle (both wheels on their rails)",
                            iterations,
                            residual: d1,
                        });
                    }
                    let p2 = p1 - d1 * (p1 - p0) / (d1 - d0);
                    p0 = p1;
                    d0 = d1;
                    p1 = p2;
                    d1 = d(p1)?;
                }
                p1
            }
        };
        let (mut r, mut l) = sides(phi)?;
        let drop = r[0].gap.min(l[0].gap);
        for c in r.iter_mut().chain(l.iter_mut()) {
            c.gap -= drop;
        }
        let radius = |c: &ContactCandidate| {
            self.params.wheel_radius + self.wheel.z(c.wheel_s).unwrap_or(f64::NAN)
        };
        let right = WheelContact {
            radii: r.iter().map(radius).collect(),
            candidates: r,
        };
        let left = WheelContact {
            radii: l.iter().map(radius).collect(),
            candidates: l,
        };
        Ok(WheelsetContact {
            lateral_shift: y_ws,
            roll: phi,
            axle_height: -drop,
            right,
            left,
        })
    }
}
