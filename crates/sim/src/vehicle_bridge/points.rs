//! Response points of the bridge besides the output point (`[output] points`): deflection,
//! velocity and acceleration at each, from the modal state,
//! w(x, t) = Σ_j w_j(x) q_j(t) (and its first and second time derivatives), with the mode
//! shapes w_j(x) evaluated once when the points are set. SI units: x and w in m.

use beam::Derivative;

use super::error::invalid;
use super::{Simulation, VehicleBridgeError};

/// Largest number of response points (as the scenario files allow).
pub const MAX_POINTS: usize = crate::config::checks::MAX_POINTS;

/// The response points and their mode shapes (point i's m shapes at `shapes[i m..(i + 1) m]`).
#[derive(Debug, Default, Clone)]
pub(super) struct ResponsePoints {
    pub(super) x: Vec<f64>,
    pub(super) shapes: Vec<f64>,
}

/// Σ_j s_j u_j: the physical value at a point of the modal vector `u` (its first `s.len()`
/// entries are the modal coordinates).
fn modal_sum(s: &[f64], u: &[f64]) -> f64 {
    s.iter().zip(u).map(|(s, u)| s * u).sum()
}

impl Simulation {
    /// Sets the bridge's response points \[m\] (each within the span, at most
    /// [`MAX_POINTS`]; `output.points` names them in errors). Replaces the previous ones.
    pub fn set_output_points(&mut self, x: &[f64]) -> Result<(), VehicleBridgeError> {
        let length = self.scenario.bridge.length();
        if x.len() > MAX_POINTS {
            return Err(invalid(
                "output.points (count)",
                x.len() as f64,
                &format!("at most {MAX_POINTS} points"),
            ));
        }
        if let Some(&bad) = x
            .iter()
            .find(|&&p| !(p.is_finite() && (0.0..=length).contains(&p)))
        {
            return Err(invalid(
                "output.points",
                bad,
                &format!("a response point must lie on the bridge, 0 ≤ x ≤ {length} m"),
            ));
        }
        let m = self.scenario.bridge.n_modes();
        let mut shapes = vec![0.0; x.len() * m];
        for (&p, s) in x.iter().zip(shapes.chunks_exact_mut(m.max(1))) {
            self.scenario.bridge.eval_all(p, Derivative::Shape, s)?;
        }
        self.points = ResponsePoints {
            x: x.to_vec(),
            shapes,
        };
        Ok(())
    }

    /// The response points \[m\] ([`Self::set_output_points`]; empty by default).
    pub fn output_points(&self) -> &[f64] {
        &self.points.x
    }

    /// Deflection \[m\], velocity \[m/s\] and acceleration \[m/s²\] of the bridge at response
    /// point `i` (down positive, as at the output point).
    pub fn point_response(&self, i: usize) -> (f64, f64, f64) {
        let m = self.scenario.bridge.n_modes();
        let s = &self.points.shapes[i * m..(i + 1) * m];
        (
            modal_sum(s, self.stepper.q()),
            modal_sum(s, self.stepper.v()),
            modal_sum(s, self.stepper.a()),
        )
    }
}
