//! Elastic half-space normal contact, solved the way CONTACT solves it.
//!
//! Two elastic (or one rigid) bodies touch over a small, almost flat area, so each is
//! modelled as an elastic half-space (references.md §C2.1, §3). Given the undeformed gap h(x, y)
//! on a grid of rectangular elements (the potential contact area) and the approach δ or the
//! total force F_n, [`NormalSolver`] finds the pressure p ≥ 0 with
//! e = h − δ + A p = 0 in contact and e > 0, p = 0 outside, where A holds Love's influence
//! coefficients for piecewise-constant pressure ([`influence`]). Products with A are
//! zero-padded FFT convolutions ([`convolution`]); the solver is the bound-constrained
//! conjugate-gradient method NormCG with an FFT preconditioner ([`normcg`]). The solvers are
//! generic over the influence operator ([`operator`]): the FFT one by default, the direct
//! O(n²) sums of the closed-form coefficients as the slow oracle.
//!
//! The tangential problem with Coulomb friction — shift (Cattaneo–Mindlin), steady and
//! transient rolling — is solved on the same grid by [`TangentialSolver`] ([`tangential`];
//! ConvexGS/SteadyGS, references.md §C3.5), with the normal–tangential coupling of dissimilar
//! materials in [`coupled`]; the simplified theories are Kalker's linear theory
//! ([`linear_theory`]) and FASTSIM ([`fastsim`](mod@fastsim)); [`strategy`] chooses between a
//! coupled and a sequential solve. User documentation: docs/tangential.md.
//!
//! [`law`] packages the normal problem as force laws F(δ) a multibody code can embed (Hertz,
//! the BEM solver at prescribed approach, damping as a decorator, rigid contact as a
//! constraint); docs/contact_law.md.
//!
//! Units are SI: metres, newtons, pascals. Pressure is positive in compression; the
//! approach is positive when the undeformed bodies overlap. Grids store element (ix, iy) at
//! index `iy * nx + ix`.
//!
//! ```
//! use halfspace::{GapShape, Grid, Material, NormalLoad, NormalSolver, SolverOptions, auto_grid};
//! let material = Material::identical(210e9, 0.3)?;
//! let shape = GapShape::Sphere { radius: 0.01 };
//! let load = NormalLoad::Force(1000.0);
//! let grid = auto_grid(&shape, &material, load, 48)?;
//! let mut solver = NormalSolver::new(grid, material)?;
//! let solution = solver.solve(&shape.sample(&grid)?, load, &SolverOptions::default())?;
//! let hertz = shape.hertz(&material, load).unwrap();
//! assert!((solution.approach / hertz.approach - 1.0).abs() < 0.01);
//! # Ok::<(), halfspace::ContactError>(())
//! ```

pub mod convolution;
pub mod coupled;
pub mod error;
pub mod fastsim;
pub mod gap;
pub mod grid;
pub mod hertz;
pub mod influence;
pub mod law;
mod linalg;
pub mod linear_theory;
pub mod material;
pub mod normcg;
pub mod operator;
pub mod solution;
pub mod strategy;
pub mod tangential;

pub use coupled::{
    CoupledOptions, CoupledProblem, CoupledSolution, solve_coupled, solve_coupled_step,
};
pub use error::ContactError;
pub use fastsim::{FastsimInput, FastsimSolution, fastsim};
pub use gap::{AUTO_GRID_ELEMENTS, AUTO_GRID_MARGIN, GapShape, auto_grid};
pub use grid::Grid;
pub use hertz::{Hertz, LineHertz, curvatures_from_radii};
pub use linear_theory::{CreepCoefficients, creep_coefficients, linear_forces};
pub use material::{Body, Material};
pub use normcg::{NormalLoad, NormalSolver, SolverOptions};
pub use operator::{
    DenseInfluence, DirectInfluence, DirectTangentialInfluence, FftInfluence,
    FftTangentialInfluence, InfluenceOperator, NormalInfluence, TangentialInfluenceOperator,
    TangentialKernel,
};
pub use solution::NormalSolution;
pub use strategy::{TangentialMethod, TangentialStrategy, tangential_strategy};
pub use tangential::{
    CoarseProducts, Creepages, ElementState, NkPreconditioner, RollingLoad, ShiftLoad,
    SteadySolver, StepMotion, TangentialOptions, TangentialSolution, TangentialSolver,
};
