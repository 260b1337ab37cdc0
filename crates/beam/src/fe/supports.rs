//! Supports (pinned, clamped, elastic bearings) and point masses of the finite-element beam.

/// Kind of a support at a point of the beam.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SupportKind {
    /// w = 0.
    Pinned,
    /// w = 0 and θ = 0.
    Clamped,
    /// Elastic bearing: translational spring k_w \[N/m\] and rotational spring k_θ \[N m/rad\].
    Spring {
        /// Translational stiffness \[N/m\].
        translational: f64,
        /// Rotational stiffness \[N m/rad\].
        rotational: f64,
    },
}

/// A support at position `x` (a node is placed there).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointSupport {
    /// Position \[m\].
    pub x: f64,
    /// Support kind.
    pub kind: SupportKind,
}

/// A lumped mass at position `x` (a node is placed there).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointMass {
    /// Position \[m\].
    pub x: f64,
    /// Mass \[kg\].
    pub mass: f64,
    /// Rotary inertia \[kg m²\].
    pub rotary_inertia: f64,
}
