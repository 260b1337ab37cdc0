//! Rigid contact-point search between a placed wheel and a placed rail profile: the local
//! minima of the vertical distance, every one a candidate (tread, flange) (references.md
//! §W2.2).
//!
//! For a wheelset at a prescribed lateral position, the rigid contact points are where the
//! vertical distance g(Y) = Z_wheel(Y) − Z_rail(Y) is smallest: lowering the wheel by
//! min g brings it into contact there. Every other local minimum of g is a further candidate
//! (a second patch when the wheel is pressed in by more than its separation). At a smooth
//! minimum both surfaces have the same slope; the contact angle is γ = atan(dZ_rail/dY).

use crate::error::WheelRailError;
use crate::placed::PlacedProfile;

/// Lateral sampling step of the search \[m\] before each minimum is refined.
pub const SEARCH_STEP: f64 = 1e-4;

/// Two neighbouring minima are distinct candidates only when the gap between them rises by
/// more than this above the larger of the two \[m\]; otherwise they are one conformal zone
/// (e.g. the R13 flange root of S1002 on the R13 gauge corner of 60E1, where the gap is zero
/// to rounding over a whole arc) and the smaller one is kept.
pub const DISTINCT_RISE: f64 = 1e-8;

/// One local minimum of the vertical distance between wheel and rail.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactCandidate {
    /// Lateral position in the track frame \[m\].
    pub y: f64,
    /// Height of the rail surface there \[m\].
    pub z: f64,
    /// The rail profile's own lateral coordinate of the point \[m\].
    pub rail_y: f64,
    /// The wheel profile's own lateral coordinate of the point \[m\].
    pub wheel_s: f64,
    /// Vertical distance between the surfaces at the minimum \[m\].
    pub gap: f64,
    /// dZ_rail/dY at the point (in the track frame).
    pub rail_slope: f64,
    /// dZ_wheel/dY at the point (equal to the rail's at a smooth minimum).
    pub wheel_slope: f64,
    /// Curvature of the rail profile in the cross-section \[1/m\] (convex head < 0).
    pub rail_curvature: f64,
    /// Curvature of the wheel surface curve in the cross-section \[1/m\] (a concave-up
    /// tread > 0 … as seen from below; a straight cone 0).
    pub wheel_curvature: f64,
}

impl ContactCandidate {
    /// The contact angle γ = atan(dZ_rail/dY) \[rad\].
    pub fn contact_angle(&self) -> f64 {
        self.rail_slope.atan()
    }
}

/// Every local minimum of the vertical distance, ordered by gap (smallest first).
pub fn search(
    wheel: &PlacedProfile<'_>,
    rail: &PlacedProfile<'_>,
) -> Result<Vec<ContactCandidate>, WheelRailError> {
    let (wl, wh) = wheel.y_range();
    let (rl, rh) = rail.y_range();
    let (lo, hi) = (wl.max(rl), wh.min(rh));
    if hi - lo < 4.0 * SEARCH_STEP {
        return Err(WheelRailError::NoOverlap {
            lateral_shift: f64::NAN,
        });
    }
    let gap = |y: f64| -> Option<f64> { Some(wheel.at(y)?.z - rail.at(y)?.z) };
    let n = ((hi - lo) / SEARCH_STEP).ceil() as usize;
    let ys: Vec<f64> = (0..=n)
        .map(|i| lo + (hi - lo) * i as f64 / n as f64)
        .collect();
    let gs: Vec<f64> = ys
        .iter()
        .map(|&y| gap(y).unwrap_or(f64::INFINITY))
        .collect();
    let mut out: Vec<(usize, ContactCandidate)> = Vec::new();
    for i in 1..n {
        if gs[i] <= gs[i - 1] && gs[i] < gs[i + 1] {
            let y = golden_min(&|y| gap(y).unwrap_or(f64::INFINITY), ys[i - 1], ys[i + 1]);
            let y = refine_on_slopes(wheel, rail, y, ys[i - 1], ys[i + 1]);
            let (Some(w), Some(r)) = (wheel.at(y), rail.at(y)) else {
                continue;
            };
            let cand = ContactCandidate {
                y,
                z: r.z,
                rail_y: r.local,
                wheel_s: w.local,
                gap: w.z - r.z,
                rail_slope: r.slope,
                wheel_slope: w.slope,
                rail_curvature: r.curvature,
                wheel_curvature: w.curvature,
            };
            // Merge with the previous minimum when no real ridge separates them.
            if let Some((j, prev)) = out.last().copied() {
                let ridge = gs[j..=i].iter().copied().fold(f64::NEG_INFINITY, f64::max);
                if ridge - prev.gap.max(cand.gap) < DISTINCT_RISE {
                    if cand.gap < prev.gap {
                        *out.last_mut().expect("non-empty") = (i, cand);
                    }
                    continue;
                }
            }
            out.push((i, cand));
        }
    }
    let mut out: Vec<ContactCandidate> = out.into_iter().map(|(_, c)| c).collect();
    out.sort_by(|a, b| a.gap.total_cmp(&b.gap));
    Ok(out)
}

/// The minimum's position from the equal-slope condition: the gap's minimum locates Y only
/// to about √(2ε/κ) (1e-8 m), its derivative to ε/κ. Bisection on the slope difference
/// within the bracket, when it changes sign there; otherwise the golden-section point.
fn refine_on_slopes(
    wheel: &PlacedProfile<'_>,
    rail: &PlacedProfile<'_>,
    y: f64,
    lo: f64,
    hi: f64,
) -> f64 {
    let d = |y: f64| -> Option<f64> { Some(wheel.at(y)?.slope - rail.at(y)?.slope) };
    let h = (hi - lo) * 1e-3;
    let (mut a, mut b) = ((y - h).max(lo), (y + h).min(hi));
    let (Some(mut da), Some(db)) = (d(a), d(b)) else {
        return y;
    };
    if da * db > 0.0 {
        return y;
    }
    for _ in 0..80 {
        let m = 0.5 * (a + b);
        let Some(dm) = d(m) else {
            return y;
        };
        if da * dm <= 0.0 {
            b = m;
        } else {
            a = m;
            da = dm;
        }
        if b - a < 1e-15 {
            break;
        }
    }
    0.5 * (a + b)
}

/// Golden-section minimum of a unimodal `f` on [a, b], to 1e-11 m.
fn golden_min(f: &dyn Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let r = 0.5 * (5f64.sqrt() - 1.0);
    let mut c = b - r * (b - a);
    let mut d = a + r * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    while b - a > 1e-11 {
        if fc < fd {
            b = d;
            d = c;
            fd = fc;
            c = b - r * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + r * (b - a);
            fd = f(d);
        }
    }
    0.5 * (a + b)
}
