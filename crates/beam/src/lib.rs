//! Euler–Bernoulli bridge beams for dyncontact (no I/O).
//!
//! * [`analytic`]: exact modes of uniform beams (SS, CC, cantilever, CP, FF) with stable shapes;
//! * [`modal`]: the [`ModalBasis`] trait shared by analytic and finite-element modes;
//! * [`damping`]: modal damping ratios and Rayleigh damping;
//! * [`quadrature`]: Gauss–Legendre and composite Simpson rules;
//! * [`sdof`]: the exact piecewise-linear (Nigam–Jennings-type) modal step.

pub mod analytic;
pub mod damping;
pub mod error;
pub mod modal;
pub mod quadrature;
pub mod sdof;

pub use analytic::{AnalyticBeam, Support, UniformBeam};
pub use damping::ModalDamping;
pub use error::BeamError;
pub use modal::{Derivative, ModalBasis};
pub use quadrature::{Quadrature, QuadratureRule};
pub use sdof::PiecewiseLinearSdof;
