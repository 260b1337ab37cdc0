//! One wheel's contact with real profiles as a force law F(δ) of its vertical approach, for a
//! multibody or vehicle–bridge model (`halfspace::law::ContactLaw`; references.md §W3.2).
//!
//! The wheelset's lateral shift and roll are fixed when the law is made (the rigid contact
//! geometry is computed once); each evaluation solves every patch of the wheel at the vertical
//! approach δ (normal approach δ cos γ per patch) and returns the vertical force
//! F = Σ F_n cos γ, its tangent k = Σ cos²γ dF_n/dδ_n from the solver's sensitivities, and the
//! stored energy W = Σ ½ ΔA Σ p_e u_e (Clapeyron: the work of F over δ). One column at ξ = 0:
//! a column gap correction c(0) shifts the approach to δ − c(0).

use halfspace::law::{ContactLaw, LawOutput, single_column_approach};
use halfspace::{ContactError, Grid, Material};

use crate::error::WheelRailError;
use crate::gap::Side;
use crate::patches::{PatchOptions, WheelLoad, WheelSolution, solve_wheel};
use crate::wheelset::{Roll, Wheelset, WheelsetContact};

/// Smallest approach evaluated \[m\]; below it the force is zero.
pub const MIN_APPROACH: f64 = 1e-9;

/// Relative force tolerance of [`ProfileLaw`]'s static approach: F(δ) = W to 1e-10.
pub const STATIC_TOL: f64 = 1e-10;

/// Newton iterations allowed for the static approach.
const STATIC_ITERATIONS: usize = 30;

/// The vertical contact law of one wheel on its rail.
#[derive(Debug)]
pub struct ProfileLaw {
    wheelset: Wheelset,
    contact: WheelsetContact,
    side: Side,
    material: Material,
    options: PatchOptions,
    last: Option<WheelSolution>,
    columns: [f64; 1],
}

fn to_contact_error(e: WheelRailError) -> ContactError {
    match e {
        WheelRailError::Contact { source, .. } => source,
        _ => ContactError::NoContact {
            reason: "the wheel–rail geometry failed (see the wheel–rail case for details)",
        },
    }
}

impl ProfileLaw {
    /// The law of the `side` wheel of `wheelset` at lateral shift `lateral_shift` \[m\] with
    /// the roll that keeps both wheels on their rails.
    pub fn new(
        wheelset: Wheelset,
        lateral_shift: f64,
        side: Side,
        material: Material,
        options: PatchOptions,
    ) -> Result<Self, WheelRailError> {
        Self::with_roll(
            wheelset,
            lateral_shift,
            Roll::Equilibrium,
            side,
            material,
            options,
        )
    }

    /// The law of the `side` wheel of `wheelset` at lateral shift `lateral_shift` \[m\] with
    /// the roll `roll` (the equilibrium one or prescribed).
    pub fn with_roll(
        wheelset: Wheelset,
        lateral_shift: f64,
        roll: Roll,
        side: Side,
        material: Material,
        options: PatchOptions,
    ) -> Result<Self, WheelRailError> {
        let contact = wheelset.contact(lateral_shift, roll)?;
        Ok(ProfileLaw {
            wheelset,
            contact,
            side,
            material,
            options,
            last: None,
            columns: [0.0],
        })
    }

    /// The rigid contact geometry the law uses.
    pub fn rigid_contact(&self) -> &WheelsetContact {
        &self.contact
    }

    /// The last evaluation's patches.
    pub fn last_solution(&self) -> Option<&WheelSolution> {
        self.last.as_ref()
    }

    fn solve(&self, load: WheelLoad) -> Result<WheelSolution, ContactError> {
        solve_wheel(
            &self.wheelset,
            &self.contact,
            self.side,
            &self.material,
            load,
            &self.options,
        )
        .map_err(to_contact_error)
    }
}

impl ContactLaw for ProfileLaw {
    fn name(&self) -> &'static str {
        "bem_profiles"
    }

    fn columns(&self) -> &[f64] {
        &self.columns
    }

    fn evaluate(
        &mut self,
        delta: f64,
        column_gap: &[f64],
        column_force: &mut [f64],
        _tangent: bool,
    ) -> Result<LawOutput, ContactError> {
        let d = single_column_approach(delta, column_gap, column_force)?;
        if d < MIN_APPROACH {
            self.last = None;
            column_force.iter_mut().for_each(|f| *f = 0.0);
            return Ok(LawOutput {
                tangent_fresh: true,
                ..LawOutput::default()
            });
        }
        let sol = self.solve(WheelLoad::VerticalApproach(d))?;
        let mut out = LawOutput {
            force: sol.vertical_force,
            tangent_fresh: true,
            ..LawOutput::default()
        };
        for p in &sol.patches {
            let c = p.contact_angle.cos();
            let s = &p.solution;
            out.stiffness += c * c * s.dfn_dapproach.unwrap_or(0.0);
            out.energy += 0.5
                * s.grid.element_area()
                * s.pressure
                    .iter()
                    .zip(&s.displacement)
                    .map(|(p, u)| p * u)
                    .sum::<f64>();
            out.max_pressure = out.max_pressure.max(s.max_pressure);
            out.iterations += s.iterations;
        }
        if let Some(main) = sol
            .patches
            .iter()
            .max_by(|a, b| a.normal_force.total_cmp(&b.normal_force))
        {
            let (a, b) = main.solution.patch_half_widths();
            out.patch_length = 2.0 * a;
            out.patch_width = 2.0 * b;
        }
        if let Some(f) = column_force.first_mut() {
            *f = out.force;
        }
        self.last = Some(sol);
        Ok(out)
    }

    fn static_approach(&mut self, force: f64) -> Result<f64, ContactError> {
        if !(force.is_finite() && force > 0.0) {
            return Err(ContactError::InvalidParameter {
                name: "force",
                value: force,
                reason: "must be positive",
            });
        }
        // The force solve sizes its grids from a Hertz estimate of the load, an evaluation
        // from its approach: their discretisations differ (8.5e-4 in F for S1002/60E1 on
        // 16 × 16 elements). Newton on the evaluations themselves, from the force solve's
        // approach, makes F(δ) = force to STATIC_TOL, so a simulation starting at δ is in
        // equilibrium with the law it steps with.
        let mut d = self
            .solve(WheelLoad::VerticalForce(force))?
            .vertical_approach;
        let mut column = [0.0];
        let mut residual = f64::NAN;
        for _ in 0..STATIC_ITERATIONS {
            let out = self.evaluate(d, &[0.0], &mut column, true)?;
            residual = out.force / force - 1.0;
            if residual.abs() <= STATIC_TOL {
                return Ok(d);
            }
            let next = if out.stiffness > 0.0 {
                d + (force - out.force) / out.stiffness
            } else {
                d * (force / out.force.max(f64::MIN_POSITIVE)).powf(2.0 / 3.0)
            };
            // Hertz-like laws: the step stays within a factor 2 of the approach.
            d = next.clamp(0.5 * d, 2.0 * d);
        }
        Err(ContactError::InvalidParameter {
            name: "force",
            value: force * (1.0 + residual),
            reason: "the profile law's static approach did not reach this force within 1e-10 in 30 Newton iterations (the value is the force reached)",
        })
    }

    fn pressure_field(&self) -> Option<(&Grid, &[f64])> {
        let sol = self.last.as_ref()?;
        let main = sol
            .patches
            .iter()
            .max_by(|a, b| a.normal_force.total_cmp(&b.normal_force))?;
        Some((&main.solution.grid, &main.solution.pressure))
    }
}
