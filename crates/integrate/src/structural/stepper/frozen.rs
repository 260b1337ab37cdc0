//! DOFs frozen at rest: left out of the work of an implicit step.
//!
//! A caller that knows some DOFs stay exactly at rest over the coming steps (e.g. a vehicle
//! standing in static equilibrium on a rigid track, uncoupled from the rest of the system) can
//! freeze them: their velocity and acceleration are set to zero and their displacement is
//! kept, so the predictors are `q̃ = q_n`, `ṽ = 0` exactly, and the step skips their rows (the
//! predictors, the history force, the effective load and the corrector cost nothing for them).
//! The rows of the other DOFs are computed with the same operations in the same order as
//! without freezing, provided no frozen DOF is coupled to them through `M` or `C` with a
//! non-zero velocity or acceleration — which freezing guarantees (theirs are zero).

use std::ops::Range;

use super::StructuralStepper;
use crate::IntegrateError;

impl StructuralStepper {
    /// Freezes the DOFs `dofs` at rest (module documentation) until the next call, which
    /// replaces the set (an empty `dofs` unfreezes every DOF); a restart unfreezes every DOF.
    /// Frozen DOFs get `v = a = 0` now and keep their `q`: [`step_equation`](Self::step_equation)
    /// gives them `q̃ = q`, `ṽ = 0` and zero rows of `h` and of the effective load, and
    /// [`finish_step`](Self::finish_step) leaves them unchanged (their entries of `q_new` are
    /// not used). Only for the implicit methods (an explicit step would move them).
    pub fn freeze(&mut self, dofs: &[usize]) -> Result<(), IntegrateError> {
        let n = self.q.len();
        if self.method.is_explicit() && !dofs.is_empty() {
            return Err(IntegrateError::InvalidParameter {
                name: "frozen DOFs",
                reason: format!(
                    "`{}` is explicit: only implicit steps can leave DOFs out",
                    self.method.name()
                ),
            });
        }
        if let Some(&i) = dofs.iter().find(|&&i| i >= n) {
            return Err(IntegrateError::InvalidParameter {
                name: "frozen DOFs",
                reason: format!("index {i} (must be < {n})"),
            });
        }
        self.frozen.clear();
        let mut sorted = dofs.to_vec();
        sorted.sort_unstable();
        sorted.dedup();
        for i in sorted {
            self.v[i] = 0.0;
            self.a[i] = 0.0;
            self.a_prev[i] = 0.0;
            match self.frozen.last_mut() {
                Some(last) if last.end == i => last.end = i + 1,
                _ => self.frozen.push(i..i + 1),
            }
        }
        Ok(())
    }

    /// The frozen DOFs as sorted, disjoint ranges.
    pub fn frozen(&self) -> &[Range<usize>] {
        &self.frozen
    }
}
