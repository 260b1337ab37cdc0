//! Euler–Bernoulli bridge beams for dyncontact (no I/O).
//!
//! * [`analytic`]: exact modes of uniform beams (SS, CC, cantilever, CP, FF) with stable shapes;
//! * [`modal`]: the [`ModalBasis`] trait shared by analytic and finite-element modes;
//! * [`fe`]: Hermite finite-element beams (stepped sections, multi-span, bearings, masses);
//! * [`damping`]: modal damping ratios and Rayleigh damping;
//! * [`quadrature`]: Gauss–Legendre and composite Simpson rules;
//! * [`loads`]: modal point and distributed loads, quasi-static response;
//! * [`moving`]: moving forces and axle trains, time histories and amplification factors;
//! * [`closed_form`]: Frýba's series for a moving force on a simply supported beam;
//! * [`sdof`]: the exact piecewise-linear (Nigam–Jennings-type) modal step;
//! * [`track`]: the railway track (rail on discrete pads, sleepers and ballast) over approach,
//!   bridge and exit;
//! * [`bench`](mod@bench): fixed workloads for the benchmark driver.
//!
//! ```
//! use beam::{AnalyticBeam, ModalBasis, ModalDamping, MovingLoadSettings, MovingLoads, Support, UniformBeam};
//!
//! // Frýba's 25 m bridge (references.md §D1.3) and a 56.4 kN force at 27.78 m/s.
//! let bridge = UniformBeam::new(25.0, 2.87e9 * 2.90, 2303.0)?;
//! let modes = AnalyticBeam::new(Support::SimplySupported, bridge, 10)?;
//! assert!((modes.circular_frequencies()[0] - 30.02).abs() < 0.01);
//! let loads = MovingLoads::single(56.4e3, 27.78)?;
//! let run = beam::simulate_moving_loads(
//!     &modes,
//!     &ModalDamping::Uniform(0.02),
//!     &loads,
//!     &MovingLoadSettings::new(1e-3, 0.2),
//!     &[12.5],
//! )?;
//! let daf = run.dynamic_amplification(0)?;
//! assert!(daf > 1.0 && daf < 1.2);
//! # Ok::<(), beam::BeamError>(())
//! ```

pub mod analytic;
mod banded;
pub mod bench;
pub mod closed_form;
pub mod damping;
pub mod error;
pub mod fe;
pub mod loads;
pub mod modal;
pub mod moving;
pub mod passage;
pub mod quadrature;
pub mod sdof;
pub mod track;

pub use analytic::{AnalyticBeam, Support, UniformBeam};
pub use damping::ModalDamping;
pub use error::BeamError;
pub use fe::{
    EigenReduction, FeBeam, FeModes, PointMass, PointSupport, Section, StaticDeflection,
    SupportKind,
};
pub use loads::DistributedLoadProjector;
pub use modal::{Derivative, ModalBasis};
pub use moving::{
    Axle, ModalIntegrator, MovingLoadResponse, MovingLoadSettings, MovingLoads, StepProgress,
    simulate_moving_loads, simulate_moving_loads_observed,
};
pub use passage::{
    PassagePeaks, PassagePlan, PassageWork, sine_amplitudes, sine_shape_dot, sine_shapes,
};
pub use quadrature::{Quadrature, QuadratureRule};
pub use sdof::PiecewiseLinearSdof;
