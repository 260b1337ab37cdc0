//! The wheel–rail contact of each wheel, as a [`halfspace::law::ContactModel`].
//!
//! A law returns, for a prescribed approach δ \[m\] (positive when wheel and rail overlap), the
//! normal force F(δ) \[N\], its tangent k_c = dF/dδ \[N/m\] and the force carried by each column
//! of its grid (positions ξ_i relative to the wheel, along the track), from which the
//! simulation forms the modal loads I_j = Σ_i F_i w_j(x_wheel + ξ_i) (∫ p w_j dx of references.md §D4.4,
//! Σ_e p_e ΔA w_j(x_e)).
//!
//! * `hertz`: [`HertzPoint`], the closed-form elliptic Hertz spring F = C_H δ^{3/2} for δ > 0,
//!   else 0 (references.md §C4.1; references.md §D2.3), with the gap curvatures
//!   A = 1/(2R_w) along the track and B = 1/(2R_r) across it; k_c = 1.5 F/δ. A point contact
//!   (one column at ξ = 0, whose column term is zero).
//! * `bem`: [`BemLaw::wheel_on_rail`], the half-space solver (NormCG at prescribed approach,
//!   warm-started from the previous call) on an n × n grid under the wheel, with the undeformed
//!   gap h(ξ, y) = R_w − √(R_w² − ξ²) (exact wheel circle) + R_r − √(R_r² − y²) (transverse
//!   rail-head circle) + c(ξ), where the column term c(ξ) = \[w(x+ξ) − w(x)\] −
//!   \[r(x+ξ) − r(x)\] carries the beam deflection and the irregularity at each grid column
//!   relative to the wheel point. k_c = dF/dδ from the solver's sensitivity solve, computed
//!   when the coupling asks for a tangent or has none yet ([`TangentPolicy::RequestedOrMissing`]).
//! * `bem` with `[contact.profiles]`: [`wheelrail::ProfileLaw`], the patches of real wheel
//!   and rail profiles at a fixed lateral shift (module [`profiles`](super::profiles)); one
//!   column at ξ = 0.
//! * `rigid`: [`RigidConstraint`], no force law; the simulation imposes δ = 0 while F > 0 with
//!   a Lagrange multiplier (the wheel follows the rail).

use std::sync::Arc;

use halfspace::law::{
    BemLaw, BemOptions, ContactModel as LawModel, HertzPoint, RigidConstraint, SharedTable,
    TangentPolicy,
};
use halfspace::{ContactError, Grid, Material, SolverOptions};

use super::{ContactModel, VehicleBridgeError};

/// Elastic constants and geometry shared by the laws.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactGeometry {
    /// Wheel rolling radius R_w \[m\].
    pub wheel_radius: f64,
    /// Transverse radius of the rail head R_r \[m\].
    pub rail_profile_radius: f64,
    /// Young's modulus of wheel and rail \[Pa\].
    pub youngs_modulus: f64,
    /// Poisson's ratio of wheel and rail.
    pub poisson_ratio: f64,
}

impl ContactGeometry {
    /// Validates the geometry and returns the combined material (references.md §C3.1).
    pub fn material(&self) -> Result<Material, VehicleBridgeError> {
        for (name, v) in [
            ("contact.wheel_radius", self.wheel_radius),
            ("contact.rail_profile_radius", self.rail_profile_radius),
            ("contact.E", self.youngs_modulus),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(VehicleBridgeError::InvalidParameter {
                    name: name.to_string(),
                    value: v,
                    reason: "must be positive and finite".to_string(),
                });
            }
        }
        let nu = self.poisson_ratio;
        if !nu.is_finite() || nu >= 0.5 || nu <= -1.0 {
            return Err(VehicleBridgeError::InvalidParameter {
                name: "contact.nu".to_string(),
                value: nu,
                reason: "must be in (-1, 0.5)".to_string(),
            });
        }
        Material::identical(self.youngs_modulus, nu).map_err(VehicleBridgeError::from)
    }

    /// Gap curvatures (A along the track, B across) \[1/m\].
    pub fn curvatures(&self) -> (f64, f64) {
        (0.5 / self.wheel_radius, 0.5 / self.rail_profile_radius)
    }

    /// The Hertz law of the geometry (module documentation).
    pub fn hertz(&self) -> Result<HertzPoint, VehicleBridgeError> {
        let material = self.material()?;
        let (a, b) = self.curvatures();
        Ok(HertzPoint::elliptic(a, b, &material)?)
    }

    /// The boundary-element law (module documentation) on an `n × n` grid sized for forces up
    /// to `max_force` \[N\] (half-widths of 1.25 × the Hertz semi-axes at `max_force`), NormCG
    /// tolerance `tol`, full solves reused within the estimated relative force error
    /// `reuse_tol` (0: none; [`BemOptions::reuse_tol`]).
    pub fn bem(
        &self,
        n: usize,
        max_force: f64,
        tol: f64,
        reuse_tol: f64,
    ) -> Result<BemLaw, VehicleBridgeError> {
        if !(4..=512).contains(&n) {
            return Err(VehicleBridgeError::InvalidParameter {
                name: "contact.grid".to_string(),
                value: n as f64,
                reason: "must be in 4..=512 elements per direction".to_string(),
            });
        }
        if !(tol.is_finite() && tol > 0.0) {
            return Err(VehicleBridgeError::InvalidParameter {
                name: "contact.bem_tol".to_string(),
                value: tol,
                reason: "must be positive".to_string(),
            });
        }
        let material = self.material()?;
        let options = BemOptions {
            solver: SolverOptions {
                tol,
                max_iter: 500,
                // dF/dδ is only the quasi-Newton tangent: 1e-4 relative is far more accurate
                // than the iteration needs (it converges in ~1 iteration per step) and halves
                // the cost of the warm-started sensitivity solve. The static start
                // (`static_approach`) solves with the sensitivity as well.
                sensitivity: true,
                sensitivity_tol: 1e-4,
                ..SolverOptions::default()
            },
            tangent: TangentPolicy::RequestedOrMissing,
            memoize: false,
            skip_separated: true,
            reuse_tol,
        };
        Ok(BemLaw::wheel_on_rail(
            self.wheel_radius,
            self.rail_profile_radius,
            material,
            n,
            max_force,
            options,
        )?)
    }
}

/// The response tables are refined to this fraction of `reuse_tol`: a wheel bouncing on the
/// exit track after the abutment's slope kink (lightly damped contact resonance) carries a
/// force error into the phase of its oscillation. Measured on the 8-car train of `dyncontact
/// bench coupling` (1 s, `reuse_tol = 3e-6`, against `reuse_tol = 0`): force history 5.1e-5 of
/// the peak with the table at `reuse_tol`, 1.1e-6 at a quarter of it (679 instead of 540
/// table solves), 2.3e-6 without a table.
const TABLE_TOL_FRACTION: f64 = 0.25;

/// The response tables F(δ) of the boundary-element wheels with reuse on
/// (`halfspace::law::ResponseTable`, issue #14): one per grid, design force and tolerance,
/// shared by the wheels with the same (a train's identical wheelsets), built on the first
/// evaluation on a flat, rigid, smooth track (no column corrections).
#[derive(Debug, Default)]
pub(super) struct ContactTables {
    tables: Vec<((usize, u64, u64), Arc<SharedTable>)>,
}

impl ContactTables {
    /// The table of grid `elements`, design force `max_force` \[N\] and tolerance `tol`.
    fn shared(&mut self, elements: usize, max_force: f64, tol: f64) -> Arc<SharedTable> {
        let key = (elements, max_force.to_bits(), tol.to_bits());
        if let Some((_, t)) = self.tables.iter().find(|(k, _)| *k == key) {
            return t.clone();
        }
        let table = Arc::new(SharedTable::new(max_force, tol));
        self.tables.push((key, table.clone()));
        table
    }

    /// Exact solves of the tables built so far.
    pub(super) fn solves(&self) -> usize {
        self.tables
            .iter()
            .filter_map(|(_, t)| t.built())
            .map(|t| t.solves())
            .sum()
    }
}

/// The contact of one wheel for the scenario's `model`, with the static wheel load `load`
/// \[N\] (the BEM grid is sized for 2.5 × the load); a BEM wheel with reuse on shares the
/// response table of its grid from `tables`.
pub(super) fn wheel_contact(
    model: &ContactModel,
    geometry: &ContactGeometry,
    load: f64,
    tables: &mut ContactTables,
) -> Result<LawModel, VehicleBridgeError> {
    Ok(match *model {
        ContactModel::Rigid => LawModel::Rigid(RigidConstraint::new(true)),
        ContactModel::Hertz => LawModel::Law(Box::new(geometry.hertz()?)),
        ContactModel::Bem {
            elements,
            tol,
            reuse_tol,
        } => {
            let mut law = geometry.bem(elements, 2.5 * load, tol, reuse_tol)?;
            if reuse_tol > 0.0 {
                law.share_table(tables.shared(
                    elements,
                    2.5 * load,
                    TABLE_TOL_FRACTION * reuse_tol,
                ));
            }
            LawModel::Law(Box::new(law))
        }
        ContactModel::BemProfiles(ref profiles) => {
            LawModel::Law(Box::new(profiles.law(geometry.material()?)?))
        }
    })
}

/// Whether the contact is the rigid constraint (its force is the simulation's multiplier, not
/// a force law).
pub(super) fn is_rigid(contact: &LawModel) -> bool {
    matches!(contact, LawModel::Rigid(_))
}

/// The column of a point contact (and of the rigid constraint), at ξ = 0.
const POINT_COLUMN: [f64; 1] = [0.0];

/// Column positions ξ_i of a contact relative to the wheel \[m\] (one at 0 for the rigid
/// constraint).
pub(super) fn columns(contact: &LawModel) -> &[f64] {
    match contact {
        LawModel::Law(law) => law.columns(),
        LawModel::Rigid(_) => &POINT_COLUMN,
    }
}

/// Whether the contact acts at the wheel's position only (one column at offset 0: the closed
/// forms and the rigid constraint), so that its modal load is F w(x_k).
pub(super) fn is_point(contact: &LawModel) -> bool {
    columns(contact) == [0.0]
}

/// The grid and pressure \[Pa\] of the last evaluation for laws that solve the pressure field
/// (`bem`); `None` for the closed forms and the rigid constraint.
pub(super) fn pressure_field(contact: &LawModel) -> Option<(&Grid, &[f64])> {
    match contact {
        LawModel::Law(law) => law.pressure_field(),
        LawModel::Rigid(_) => None,
    }
}

/// The error of wheel `wheel`'s contact law.
pub(super) fn wheel_error(wheel: usize) -> impl Fn(ContactError) -> VehicleBridgeError {
    move |source| VehicleBridgeError::WheelContact { wheel, source }
}

/// The full solves of the boundary-element contacts of a run and their reuse (references.md
/// §C8.4), summed over the wheels.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ContactSolves {
    /// Full NormCG solves over all wheels (the static start included).
    pub full_solves: usize,
    /// Exact solves by active-set updates of the dense factor of the last contact set
    /// instead of a NormCG solve (references.md §C8.4; `reuse_tol` > 0).
    pub factor_solves: usize,
    /// Evaluations answered by the frozen-set model without a solve.
    pub reused: usize,
    /// Largest estimated force error of a reused evaluation relative to the force of its
    /// full solve (0 without reuse); the response table's answers included.
    pub max_estimate: f64,
    /// Evaluations answered by the shared response tables F(δ) (wheels on a flat, rigid,
    /// smooth track; issue #14).
    pub table_answers: usize,
    /// Exact solves the response tables were built from (each table once, shared).
    pub table_solves: usize,
}

impl super::Simulation {
    /// The full solves and their reuse over the wheels; `None` when no wheel solves its
    /// contact (Hertz, rigid).
    pub fn contact_solves(&self) -> Option<ContactSolves> {
        let mut total: Option<ContactSolves> = None;
        for contact in &self.contacts {
            if let Some(s) = contact_law_stats(contact) {
                let t = total.get_or_insert_with(ContactSolves::default);
                t.full_solves += s.full_solves;
                t.factor_solves += s.factor_solves;
                t.reused += s.reused;
                t.max_estimate = t.max_estimate.max(s.max_estimate);
                t.table_answers += s.table_answers;
            }
        }
        if let Some(t) = total.as_mut() {
            t.table_solves = self.contact_tables.solves();
        }
        total
    }
}

fn contact_law_stats(contact: &LawModel) -> Option<halfspace::law::ReuseStats> {
    match contact {
        LawModel::Law(law) => law.reuse_stats(),
        LawModel::Rigid(_) => None,
    }
}
