//! Contact laws a multibody code can embed: the normal force as a function of the approach.
//!
//! A [`ContactLaw`] answers, for a prescribed approach δ \[m\] (positive when the undeformed
//! bodies overlap) and optional per-column gap corrections c(ξ_i) \[m\] along the rolling
//! direction, with the normal force F(δ) \[N\] (≥ 0), its tangent k = dF/dδ \[N/m\], the stored
//! elastic energy W(δ) = ∫₀^δ F dδ' \[J\], the force carried by each grid column and, for the
//! laws that solve it, the pressure field. Errors are [`ContactError`]s.
//!
//! | law | F(δ) | k | W | pressure field |
//! |---|---|---|---|---|
//! | [`HertzPoint`] | C δ^{3/2} (references.md §C4.1) | 1.5 F/δ | 0.4 F δ | `None` |
//! | [`HertzLine`] | L F'(δ), δ(F') logarithmic to a reference depth d (references.md §C4.1) | L/(dδ/dF') | L (F'δ − ∫δ dF') | `None` |
//! | [`BemLaw`] | ΔA Σ p_e, NormCG at prescribed δ | sensitivity solve | ½ ΔA Σ p_e u_e | the grid and p |
//!
//! Decorators and constraints:
//! * [`Damped`] wraps any law: F = max(0, F_el(δ) + c δ̇) for δ > 0, else 0 (linear surface
//!   damping; the clamp keeps a surface from pulling).
//! * [`RigidConstraint`] is NOT a force law: rigid contact is the complementarity condition
//!   g = −δ ≥ 0, F ≥ 0, g F = 0 (no overlap; δ = 0 while F > 0), whose force is a Lagrange
//!   multiplier held by the caller's integrator. Callers dispatch on [`ContactModel`].
//!
//! # Stepping a law from outside
//!
//! A steel ball (R = 10 mm, m = 0.0411 kg) hits a steel half-space at v₀ = 0.1 m/s; the
//! ball's motion m δ̈ = −F(δ) is integrated with the explicit (velocity) Verlet scheme and
//! the peak force is compared with Hertz's impact solution
//! F_max = C δ_max^{3/2}, δ_max = (5 m v₀² / (4 C))^{2/5} (energy balance ½ m v₀² = W(δ_max)).
//!
//! ```
//! use halfspace::law::{ContactLaw, HertzPoint};
//! use halfspace::Material;
//! let material = Material::identical(210e9, 0.3)?;
//! let mut law = HertzPoint::sphere(0.01, &material)?;
//! let (m, v0) = (0.0411, 0.1);
//! let (mut delta, mut rate) = (0.0_f64, v0); // approach and its rate (ball moving down)
//! let dt = 1e-8;
//! let mut force = law.evaluate(delta, &[], &mut [], false)?.force;
//! let mut peak: f64 = 0.0;
//! for _ in 0..20_000 {
//!     rate -= 0.5 * dt * force / m;
//!     delta += dt * rate;
//!     force = law.evaluate(delta, &[], &mut [], false)?.force;
//!     rate -= 0.5 * dt * force / m;
//!     peak = peak.max(force);
//! }
//! let c = law.coefficient();
//! let delta_max = (5.0 * m * v0 * v0 / (4.0 * c)).powf(0.4);
//! let closed_form = c * delta_max.powf(1.5);
//! assert!((peak / closed_form - 1.0).abs() < 1e-4, "{peak} vs {closed_form}");
//! # Ok::<(), halfspace::ContactError>(())
//! ```

mod bem;
mod damped;
mod hertz;
mod hertz_line;
mod response_table;
mod reuse;
mod rigid;
mod set_factor;
mod set_solve;

pub use bem::{BemLaw, BemOptions, ReuseStats, TABLE_STREAK, TangentPolicy};
pub use damped::{Damped, DampingModel};
pub use hertz::HertzPoint;
pub use hertz_line::HertzLine;
pub use response_table::{ResponseTable, SharedTable, TableAnswer};
pub use rigid::RigidConstraint;

use crate::error::ContactError;
use crate::grid::Grid;

/// One evaluation of a contact law. SI units.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct LawOutput {
    /// Normal force F \[N\] (≥ 0).
    pub force: f64,
    /// Tangent k = dF/dδ \[N/m\] (0 out of contact). With `tangent = false` a law may return
    /// the tangent of an earlier evaluation ([`LawOutput::tangent_fresh`] says which).
    pub stiffness: f64,
    /// Whether `stiffness` was computed at this δ.
    pub tangent_fresh: bool,
    /// Stored elastic energy W = ∫₀^δ F dδ' \[J\].
    pub energy: f64,
    /// Length of the contact patch along the rolling direction x \[m\].
    pub patch_length: f64,
    /// Width of the contact patch across it (y) \[m\].
    pub patch_width: f64,
    /// Peak pressure \[Pa\].
    pub max_pressure: f64,
    /// Iterations of the contact solver (0 for closed forms).
    pub iterations: usize,
}

/// A normal contact force law F(δ) (module documentation).
///
/// `column_gap` holds the gap corrections c(ξ_i) \[m\] of the grid columns
/// ([`ContactLaw::columns`]) added to the law's own gap (empty: no corrections);
/// `column_force` receives the force \[N\] carried by each column (empty: not wanted).
/// With `tangent = false` a law may skip computing a new tangent.
pub trait ContactLaw: std::fmt::Debug + Send {
    /// Short name for reports (`hertz`, `bem`, …).
    fn name(&self) -> &'static str;

    /// Column positions ξ_i along the rolling direction relative to the contact point \[m\]
    /// (one column at 0 for a point contact).
    fn columns(&self) -> &[f64];

    /// Evaluates the law at approach `delta` \[m\] (trait documentation).
    fn evaluate(
        &mut self,
        delta: f64,
        column_gap: &[f64],
        column_force: &mut [f64],
        tangent: bool,
    ) -> Result<LawOutput, ContactError>;

    /// Total force including rate-dependent terms F(δ, δ̇) \[N\], with the elastic evaluation.
    /// Elastic laws return F_el(δ) (rate ignored); [`Damped`] adds its damping force.
    fn total_force(&mut self, delta: f64, rate: f64) -> Result<(f64, LawOutput), ContactError> {
        let _ = rate;
        let out = self.evaluate(delta, &[], &mut [], false)?;
        Ok((out.force, out))
    }

    /// The approach δ \[m\] that carries `force` \[N\] with no column corrections.
    fn static_approach(&mut self, force: f64) -> Result<f64, ContactError>;

    /// The counts of full solves and of evaluations answered without one, for laws that
    /// solve (`bem`); `None` for closed forms.
    fn reuse_stats(&self) -> Option<ReuseStats> {
        None
    }

    /// The grid and pressure \[Pa\] of the last evaluation (x fastest) for laws that solve the
    /// pressure field; `None` for closed forms.
    fn pressure_field(&self) -> Option<(&Grid, &[f64])> {
        None
    }

    /// The pressure \[Pa\] of the last evaluation along the line y = 0, as (ξ, p) pairs.
    fn centreline_pressure(&self, out: &mut Vec<(f64, f64)>) {
        out.clear();
    }
}

/// How a contact is modelled: a compliant force law, or the rigid constraint.
#[derive(Debug)]
pub enum ContactModel {
    /// A force law F(δ) (possibly damped).
    Law(Box<dyn ContactLaw>),
    /// The unilateral rigid constraint (δ = 0 while F > 0, F ≥ 0).
    Rigid(RigidConstraint),
}

impl ContactModel {
    /// `rigid` or the law's name.
    pub fn name(&self) -> &'static str {
        match self {
            ContactModel::Law(law) => law.name(),
            ContactModel::Rigid(_) => "rigid",
        }
    }

    /// The force law, `None` for the rigid constraint.
    pub fn law_mut(&mut self) -> Option<&mut (dyn ContactLaw + 'static)> {
        match self {
            ContactModel::Law(law) => Some(law.as_mut()),
            ContactModel::Rigid(_) => None,
        }
    }
}

/// The approach δ − c₀ of a law with one column (a point or line contact), after checking
/// the column slices and that δ is finite: the input check of every one-column
/// [`ContactLaw::evaluate`], also for laws outside this crate.
pub fn single_column_approach(
    delta: f64,
    column_gap: &[f64],
    column_force: &[f64],
) -> Result<f64, ContactError> {
    check_columns(1, column_gap, column_force)?;
    crate::error::finite("approach", delta)?;
    Ok(delta - column_gap.first().copied().unwrap_or(0.0))
}

/// Hertz's semi-elliptic profile p(ξ) = p₀ √(1 − ξ²/a²) at 41 points over \[−1.25a, 1.25a\]
/// into `out` (empty for a = 0).
pub(crate) fn semi_ellipse_profile(a: f64, p0: f64, out: &mut Vec<(f64, f64)>) {
    out.clear();
    if a > 0.0 {
        for i in 0..=40 {
            let xi = 1.25 * a * (i as f64 / 20.0 - 1.0);
            out.push((xi, p0 * (1.0 - (xi / a).powi(2)).max(0.0).sqrt()));
        }
    }
}

/// Check that `column_gap` / `column_force` are empty or one value per column.
pub(crate) fn check_columns(
    columns: usize,
    column_gap: &[f64],
    column_force: &[f64],
) -> Result<(), ContactError> {
    for (name, len) in [
        ("column_gap", column_gap.len()),
        ("column_force", column_force.len()),
    ] {
        if len != 0 && len != columns {
            return Err(ContactError::SizeMismatch {
                name,
                expected: columns,
                found: len,
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests;
