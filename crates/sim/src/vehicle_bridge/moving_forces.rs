//! Moving forces in the coupled model: axles known by their load only (the `moving_forces`
//! vehicles of a train, e.g. a locomotive given by its axle loads ahead of coaches with
//! suspension). They have no DOFs and no contact: constant vertical forces F_p travelling at
//! the scenario speed c, whose generalized force on bridge mode j is
//!
//! ```text
//! P_j(t) = Σ_p F_p w_j(x_p + c t)      (x_p + c t on the span; 0 off it),
//! ```
//!
//! the moving-load term of the modal equations (references.md §D1.1). It enters the step like
//! every external load: at t_{n+1−α_f} = (1 − α_f) P(t_{n+1}) + α_f P(t_n) in the structural
//! methods (the old part through the accepted load, `accept`), at t itself in Radau5.

use beam::{Derivative, ModalBasis};

use super::VehicleBridgeError;

/// One moving force: its position at t = 0 and its magnitude.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MovingForce {
    /// Position along the track at t = 0 \[m\] (0 = left end of the span).
    pub position: f64,
    /// The force \[N\], downwards positive (an axle load).
    pub force: f64,
}

/// The modal loads of the moving forces at time `t`, `out_j += scale · P_j(t)` (m values),
/// with `shapes` as scratch (m values) and `sine` the sine-recurrence amplitudes of a simply
/// supported uniform span (`beam::sine_amplitudes`), when the bridge is one.
#[allow(clippy::too_many_arguments)]
pub(super) fn add_modal_load(
    forces: &[MovingForce],
    speed: f64,
    t: f64,
    basis: &dyn ModalBasis,
    sine: Option<&[f64]>,
    scale: f64,
    shapes: &mut [f64],
    out: &mut [f64],
) -> Result<(), VehicleBridgeError> {
    let length = basis.length();
    for p in forces {
        let x = p.position + speed * t;
        if !(0.0..=length).contains(&x) {
            continue;
        }
        match sine {
            Some(a) => beam::sine_shapes(a, length, x, shapes),
            None => basis.eval_all(x, Derivative::Shape, shapes)?,
        }
        let f = scale * p.force;
        for (o, s) in out.iter_mut().zip(shapes.iter()) {
            *o += f * s;
        }
    }
    Ok(())
}

impl super::Simulation {
    /// The modal loads of the scenario's moving forces at time `t` into `work.moving_load`
    /// (m values; zero when there are none).
    pub(super) fn moving_force_load(&mut self, t: f64) -> Result<(), VehicleBridgeError> {
        let w = &mut self.work;
        w.moving_load.fill(0.0);
        add_modal_load(
            &self.scenario.moving_forces,
            self.scenario.speed,
            t,
            &*self.scenario.bridge,
            self.sine.as_deref(),
            1.0,
            &mut w.force_shapes,
            &mut w.moving_load,
        )
    }
}
