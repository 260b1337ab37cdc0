//! Rigid contact: a unilateral constraint, not a force law.

/// The rigid (non-penetrating) contact: the complementarity conditions
/// g = −δ ≥ 0, F ≥ 0, g F = 0 (references.md §D2.3). The force is the Lagrange multiplier
/// λ of the constraint δ = 0, which only the caller's integrator can compute (it couples the
/// two bodies' equations of motion); this type holds the constraint's state and the rules of
/// the active set: the constraint is active while λ > 0, released when λ would become
/// negative (loss of contact), and re-activated when the bodies meet again (δ ≥ 0).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct RigidConstraint {
    active: bool,
    multiplier: f64,
}

impl RigidConstraint {
    /// A constraint, inactive (no contact) or active.
    pub fn new(active: bool) -> Self {
        Self {
            active,
            multiplier: 0.0,
        }
    }

    /// Whether the bodies are held together (δ = 0 imposed).
    pub fn is_active(&self) -> bool {
        self.active
    }

    /// The last contact force λ \[N\] (0 while inactive).
    pub fn force(&self) -> f64 {
        self.multiplier
    }

    /// Records the multiplier λ \[N\] the caller solved for with the constraint active and
    /// applies the complementarity rule: λ ≤ 0 releases the constraint (F = 0). Returns the
    /// contact force F = max(λ, 0).
    pub fn accept_multiplier(&mut self, multiplier: f64) -> f64 {
        if multiplier > 0.0 {
            self.active = true;
            self.multiplier = multiplier;
        } else {
            self.active = false;
            self.multiplier = 0.0;
        }
        self.multiplier
    }

    /// Checks a free (inactive) state: the bodies come into contact when the approach
    /// δ \[m\] of the free motion reaches 0; the constraint becomes active. Returns whether
    /// it is active.
    pub fn check_approach(&mut self, delta: f64) -> bool {
        if !self.active && delta >= 0.0 {
            self.active = true;
        }
        self.active
    }
}
