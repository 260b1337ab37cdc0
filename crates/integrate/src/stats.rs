//! Run statistics shared by every integrator.

/// Counters of one integration run (or of the steps taken so far).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Stats {
    /// Accepted steps.
    pub steps: usize,
    /// Rejected steps (error test failure or Newton failure).
    pub rejected_steps: usize,
    /// Evaluations of the right-hand side f (or of the force vector). For the first-order
    /// methods this excludes the evaluations spent on finite-difference Jacobians (RADAU5's
    /// `NFCN` convention; add `dim` per Jacobian evaluation to get the total).
    pub f_evals: usize,
    /// Evaluations of the Jacobian (analytic or by finite differences).
    pub jacobian_evals: usize,
    /// LU factorisations (for Radau5, a real and a complex one count as two).
    pub lu_decompositions: usize,
    /// Newton iterations, summed over all steps.
    pub newton_iterations: usize,
}
