//! Surface damping as a decorator of any contact law.

use super::{ContactLaw, LawOutput};
use crate::error::ContactError;
use crate::grid::Grid;

/// The damping force model added to the elastic force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DampingModel {
    /// Linear surface damping F_d = c δ̇ with c ≥ 0 \[N·s/m\].
    Linear { c: f64 },
}

/// A law with surface damping (the ball drop's model, references.md §D1.4):
/// F = max(0, F_el(δ) + c δ̇) while δ > 0, and F = 0 otherwise. The clamp keeps the damped
/// force from pulling (a surface cannot hold the body). The elastic part (force, tangent,
/// energy, pressure) is the wrapped law's; [`ContactLaw::evaluate`] returns it unchanged and
/// [`ContactLaw::total_force`] adds the damping.
#[derive(Debug)]
pub struct Damped<L> {
    law: L,
    model: DampingModel,
}

impl<L: ContactLaw> Damped<L> {
    /// Wraps `law`; c must be finite and ≥ 0.
    pub fn new(law: L, model: DampingModel) -> Result<Self, ContactError> {
        let DampingModel::Linear { c } = model;
        if !(c.is_finite() && c >= 0.0) {
            return Err(ContactError::InvalidParameter {
                name: "damping",
                value: c,
                reason: "must be finite and non-negative (N s/m)",
            });
        }
        Ok(Self { law, model })
    }

    /// The damping model.
    pub fn model(&self) -> DampingModel {
        self.model
    }

    /// Linear damping coefficient c \[N·s/m\].
    pub fn damping(&self) -> f64 {
        let DampingModel::Linear { c } = self.model;
        c
    }

    /// The wrapped elastic law.
    pub fn inner(&self) -> &L {
        &self.law
    }

    /// The wrapped elastic law, mutably.
    pub fn inner_mut(&mut self) -> &mut L {
        &mut self.law
    }
}

impl<L: ContactLaw> ContactLaw for Damped<L> {
    fn name(&self) -> &'static str {
        self.law.name()
    }

    fn columns(&self) -> &[f64] {
        self.law.columns()
    }

    fn evaluate(
        &mut self,
        delta: f64,
        column_gap: &[f64],
        column_force: &mut [f64],
        tangent: bool,
    ) -> Result<LawOutput, ContactError> {
        self.law.evaluate(delta, column_gap, column_force, tangent)
    }

    /// F = max(0, F_el(δ) + c δ̇) for δ > 0, else 0 (and F_el = 0 without an evaluation).
    fn total_force(&mut self, delta: f64, rate: f64) -> Result<(f64, LawOutput), ContactError> {
        if delta <= 0.0 {
            crate::error::finite("approach", delta)?;
            return Ok((0.0, LawOutput::default()));
        }
        let out = self.law.evaluate(delta, &[], &mut [], false)?;
        Ok(((out.force + self.damping() * rate).max(0.0), out))
    }

    fn static_approach(&mut self, force: f64) -> Result<f64, ContactError> {
        self.law.static_approach(force)
    }

    fn pressure_field(&self) -> Option<(&Grid, &[f64])> {
        self.law.pressure_field()
    }

    fn reuse_stats(&self) -> Option<super::ReuseStats> {
        self.law.reuse_stats()
    }

    fn centreline_pressure(&self, out: &mut Vec<(f64, f64)>) {
        self.law.centreline_pressure(out);
    }
}
