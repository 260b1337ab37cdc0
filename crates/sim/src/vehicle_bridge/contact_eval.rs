//! Contact evaluation at an iterate: mode shapes and irregularity under the wheels and
//! their contact columns, the approach, the contact forces and their modal loads.

use beam::Derivative;
use halfspace::law::{ContactModel as LawModel, LawOutput};

use super::contact::{columns, is_point, wheel_error};
use super::{Simulation, VehicleBridgeError};

impl Simulation {
    /// Mode shapes and irregularity at the wheels and their contact columns at time `t`.
    pub(super) fn wheel_geometry(&mut self, t: f64) -> Result<(), VehicleBridgeError> {
        let basis = &*self.scenario.bridge;
        let length = basis.length();
        let m = basis.n_modes();
        let w = &mut self.work;
        // Mode shapes at x (the sine recurrence on a simply supported uniform span).
        let sine = self.sine.as_deref();
        // Mode shapes at x; false (and zeros) off the span.
        let shapes_at = |x: f64, out: &mut [f64]| -> Result<bool, VehicleBridgeError> {
            if !(0.0..=length).contains(&x) {
                out.fill(0.0);
                return Ok(false);
            } else if let Some(a) = sine {
                beam::sine_shapes(a, length, x, out);
            } else {
                basis.eval_all(x, Derivative::Shape, out)?;
            }
            Ok(true)
        };
        let off = |x: f64| !(0.0..=length).contains(&x);
        for (k, spec) in self.scenario.wheels.iter().enumerate() {
            let x = spec.position + self.scenario.speed * t;
            self.samples[k].position = x;
            // A wheel that stays off the span: its shapes are zero already (`span_modes` 0
            // means every shape under it was zero or filled with zeros) and its pattern is its
            // own DOF; only the irregularity changes (the same values as the full pass).
            let columns_at = columns(&self.contacts[k]);
            if w.span_modes[k] == 0
                && w.pattern[k].len() == 1
                && off(x)
                && columns_at.iter().all(|&xi| off(x + xi))
            {
                let r = self.scenario.irregularity.height(x);
                w.r_at_wheel[k] = r;
                for (rc, &xi) in w.r_at_columns[k].iter_mut().zip(columns_at) {
                    // A column at the wheel sees the wheel's rail height (x + 0 = x).
                    *rc = if xi == 0.0 {
                        r
                    } else {
                        self.scenario.irregularity.height(x + xi)
                    };
                }
                continue;
            }
            let mut inside = shapes_at(x, &mut w.shape_at_wheel[k])?;
            w.r_at_wheel[k] = self.scenario.irregularity.height(x);
            for (i, &xi) in columns_at.iter().enumerate() {
                let xc = x + xi;
                let out = &mut w.shape_at_columns[k][i * m..(i + 1) * m];
                if xi == 0.0 {
                    out.copy_from_slice(&w.shape_at_wheel[k]);
                    w.r_at_columns[k][i] = w.r_at_wheel[k];
                } else {
                    inside |= shapes_at(xc, out)?;
                    w.r_at_columns[k][i] = self.scenario.irregularity.height(xc);
                }
            }
            // ĝ and v touch the modes only while the wheel or one of its columns is on the
            // span (off it every mode shape is zero, and so are their mode entries; the scan
            // is needed only if a point is within [0, L]).
            let on_span = inside
                && w.shape_at_wheel[k]
                    .iter()
                    .chain(&w.shape_at_columns[k])
                    .any(|&s| s != 0.0);
            if !on_span && w.span_modes[k] > 0 {
                for vector in [
                    &mut w.g_hat[k],
                    &mut w.v[k],
                    &mut w.g_act[k],
                    &mut w.v_act[k],
                ] {
                    vector[..m].fill(0.0);
                }
            }
            w.span_modes[k] = if on_span { m } else { 0 };
            let pattern = &mut w.pattern[k];
            pattern.clear();
            if on_span {
                pattern.extend(0..m);
            }
            pattern.push(self.wheel_dof[k]);
        }
        Ok(())
    }

    /// Evaluates every contact at the iterate `work.x`: approach, force, modal loads, ĝ and v.
    ///
    /// Three passes: the approach and the column gaps of every wheel; the contact laws, in
    /// parallel (rayon) when at least [`PARALLEL_LAWS`] wheels solve their contact (BEM), each
    /// law on its own data, so the results do not depend on the thread count; the modal
    /// loads, ĝ and v.
    pub(super) fn evaluate_contacts(&mut self, tangent: bool) -> Result<(), VehicleBridgeError> {
        let m = self.scenario.bridge.n_modes();
        let w = &mut self.work;
        let (live, held) = (&self.resting.live, &self.resting.held_wheel);
        for &k in live {
            let iw = self.wheel_dof[k];
            let defl = w.deflection_under(k, &w.x);
            w.delta[k] = w.approach(k, iw, &w.x);
            if let LawModel::Law(law) = &self.contacts[k] {
                for (i, &xi) in law.columns().iter().enumerate() {
                    // A column at the wheel has the wheel's shapes and rail height: its
                    // deflection is `defl` (the same sum), so its gap is exactly 0 if finite.
                    if xi == 0.0 && defl.is_finite() {
                        w.column_gap[k][i] = 0.0;
                        continue;
                    }
                    let cs = &w.shape_at_columns[k][i * m..(i + 1) * m];
                    let wc: f64 = (0..w.span_modes[k]).map(|j| w.x[j] * cs[j]).sum();
                    w.column_gap[k][i] = (wc - defl) - (w.r_at_columns[k][i] - w.r_at_wheel[k]);
                }
            }
        }
        let forces = &self.forces;
        let evaluate = |(k, (((contact, delta), gap), (column_force, out))): LawItem<'_>|
         -> Result<(), VehicleBridgeError> {
            *out = match contact {
                LawModel::Rigid(_) => {
                    column_force[0] = forces[k];
                    LawOutput {
                        force: forces[k],
                        ..LawOutput::default()
                    }
                }
                LawModel::Law(law) => law
                    .evaluate(*delta, gap, column_force, tangent)
                    .map_err(wheel_error(k))?,
            };
            Ok(())
        };
        let solving = live
            .iter()
            .filter(|&&k| super::contact::pressure_field(&self.contacts[k]).is_some())
            .count();
        if solving >= PARALLEL_LAWS {
            use rayon::prelude::*;
            let items: Vec<_> = self
                .contacts
                .iter_mut()
                .zip(&w.delta)
                .zip(&w.column_gap)
                .zip(w.column_force.iter_mut().zip(w.outputs.iter_mut()))
                .enumerate()
                .filter(|(k, _)| !held[*k])
                .collect();
            // The first error by wheel index, whatever the thread count.
            let results: Vec<Result<(), VehicleBridgeError>> =
                items.into_par_iter().map(evaluate).collect();
            results.into_iter().collect::<Result<(), _>>()?;
        } else {
            // The wheels taking part, in order (the first error by wheel index).
            for &k in live {
                let (contact, delta, gap) = (&mut self.contacts[k], &w.delta[k], &w.column_gap[k]);
                let out = (&mut w.column_force[k], &mut w.outputs[k]);
                evaluate((k, (((contact, delta), gap), out)))?;
            }
        }
        for &k in live {
            let iw = self.wheel_dof[k];
            let out = w.outputs[k];
            let shapes = &w.shape_at_wheel[k];
            let load = &mut w.modal_load[k];
            load.fill(0.0);
            let mk = w.span_modes[k];
            if mk > 0 {
                add_modal_load(&w.shape_at_columns[k], &w.column_force[k], 1.0, load);
            }
            // ĝ and v live on the modes and the wheel (`Work::pattern`); nothing else is
            // ever written, so the other entries stay zero.
            // A point contact's ĝ is exactly −w(x_k) (its load is F w(x_k)), which keeps it
            // equal across the iterations of a step (`linalg::CapacitanceWork` reuses A⁻¹ĝ).
            let point = is_point(&self.contacts[k]);
            let (gh, v) = (&mut w.g_hat[k], &mut w.v[k]);
            for j in 0..mk {
                v[j] = -shapes[j];
                gh[j] = if out.force > 0.0 && !point {
                    -load[j] / out.force
                } else {
                    -shapes[j]
                };
            }
            v[iw] = 1.0;
            gh[iw] = 1.0;
        }
        Ok(())
    }
}

/// One wheel's part of the law pass: its index, contact, approach, column gaps, and the
/// column forces and output it writes.
type LawItem<'a> = (
    usize,
    (
        ((&'a mut LawModel, &'a f64), &'a Vec<f64>),
        (&'a mut Vec<f64>, &'a mut LawOutput),
    ),
);

/// Number of wheels solving their contact (BEM) from which [`Simulation::evaluate_contacts`]
/// evaluates the laws in parallel (below it a closed form or one solve is cheaper than the
/// threads' hand-over).
pub(super) const PARALLEL_LAWS: usize = 2;

/// Adds the modal loads of one wheel, `I_j += Σ_i (scale F_i) w_j(x_k + ξ_i)` (module
/// documentation of the vehicle–bridge model), to `load` (m values): `column_force` holds the
/// column forces F_i \[N\] and `column_shapes` the m mode shapes at each column (column-major
/// by column, ncol × m).
pub(super) fn add_modal_load(
    column_shapes: &[f64],
    column_force: &[f64],
    scale: f64,
    load: &mut [f64],
) {
    let m = load.len();
    for (i, &fc) in column_force.iter().enumerate() {
        if fc != 0.0 {
            let f = scale * fc;
            let cs = &column_shapes[i * m..(i + 1) * m];
            for j in 0..m {
                load[j] += f * cs[j];
            }
        }
    }
}
