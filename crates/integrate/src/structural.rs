//! Second-order structural systems `M q'' + C q' + f_int(q) = f_ext(t)` and their time
//! integrators (references.md §D3.4, §3.5).
//!
//! # Problem
//! A [`StructuralSystem`] provides a constant mass matrix `M`, an optional constant damping
//! matrix `C`, a (possibly nonlinear) internal force `f_int(q)` with an optional tangent
//! stiffness `K_t = ∂f_int/∂q` (finite differences otherwise) and an external load `f_ext(t)`.
//! [`LinearStructure`] is a ready-made linear system `f_int = K q`; [`FirstOrderForm`] turns any
//! structural system into a first-order [`OdeSystem`](crate::ode::OdeSystem) (`y = [q, v]`) so
//! the methods of [`crate::ode`] can integrate it.
//!
//! # Methods ([`StructuralMethod`])
//! | method | kind | order | source |
//! |---|---|---|---|
//! | Störmer–Verlet (velocity form) | explicit | 2 | Hairer, Lubich & Wanner, *Geometric Numerical Integration* (2006) §I.1.4 |
//! | leapfrog (kick–drift–kick, half-step damping) | explicit | 2 (1 in the damping term) | idem; explicit FE codes |
//! | central difference = Newmark β = 0, γ = ½ | explicit | 2 | Newmark (1959) |
//! | Newmark-β (average acceleration by default) | implicit | 2 if γ = ½, else 1 | Newmark (1959), references.md §D3.5 |
//! | HHT-α, α ∈ [−1/3, 0] | implicit | 2 | Hilber, Hughes & Taylor (1977) |
//! | generalized-α by ρ∞ ∈ [0, 1] | implicit | 2 | Chung & Hulbert (1993) |
//! | backward Euler (second-order form) | implicit | 1 | references.md §D4.4 |
//!
//! # The step equation
//! Every implicit scheme is written in one form (the generalized-α form of Chung & Hulbert,
//! with backward Euler as a special predictor). For the step `n → n+1` of size Δt:
//!
//! ```text
//! q_{n+1} = q̃ + c_qa · a_{n+1},          v_{n+1} = ṽ + c_va · a_{n+1}
//! M[(1−α_m) a_{n+1} + α_m a_n] + C[(1−α_f) v_{n+1} + α_f v_n]
//!     + (1−α_f) f_int(q_{n+1}) + α_f f_int(q_n) = f_ext(t_{n+1−α_f})
//! ```
//!
//! with, for the α family, `q̃ = q_n + Δt v_n + Δt²(½−β) a_n`, `ṽ = v_n + Δt(1−γ) a_n`,
//! `c_qa = βΔt²`, `c_va = γΔt`, and for backward Euler `q̃ = q_n + Δt v_n`, `ṽ = v_n`,
//! `c_qa = Δt²`, `c_va = Δt`, `α_m = α_f = 0` (so `q_{n+1} = q_n + Δt v_{n+1}`,
//! `v_{n+1} = v_n + Δt a_{n+1}`).
//! Taking the displacement `q_{n+1}` as the unknown, the Jacobian of the balance equation is
//! `K_eff = c_M M + c_C C + c_K K_t` with `c_M = (1−α_m)/c_qa`, `c_C = (1−α_f) c_va/c_qa`,
//! `c_K = 1−α_f`.
//!
//! [`StructuralStepper::step_equation`] returns these numbers ([`StepEquation`]), and
//! [`StructuralStepper::finish_step`] applies the corrector once an outside solver (the
//! vehicle–bridge coupling, references.md §D4.2, `A·x = r + b·F` with Sherman–Morrison) has found
//! `q_{n+1}`. The built-in [`StructuralStepper::step`] solves the same equation by Newton's method
//! and calls the same corrector, so both paths share one implementation of the formulas.
//!
//! # Variable steps
//! Newmark, backward Euler, Verlet and leapfrog are one-step methods and keep their order for
//! any step sequence. The acceleration variable of HHT and generalized-α approximates
//! `q''(t_n + (α_m − α_f)Δt)`; when Δt changes by a ratio in [½, 2] it is moved to the new
//! shift by linear extrapolation before it enters `q̃`, `ṽ` and `h` (second order measured with
//! alternating steps; without it the order fell to 1.4). Larger jumps skip the correction,
//! which was found to destabilise stiff components.
//!
//! # Example: an outside solver
//! One DOF, `m q'' + k q = 0`, each implicit step solved by hand from the step equation
//! (`K_eff Δq = −R`, exact in one iteration for a linear spring):
//!
//! ```
//! use faer::Mat;
//! use integrate::structural::{LinearStructure, StructuralMethod, StructuralStepper};
//!
//! let (m, k) = (2.0, 8.0);
//! let mut spring = LinearStructure::new(
//!     Mat::from_fn(1, 1, |_, _| m),
//!     None,
//!     Mat::from_fn(1, 1, |_, _| k),
//!     |_t: f64, f: &mut [f64]| f[0] = 0.0,
//! )?;
//! let method = StructuralMethod::by_name("generalized_alpha", &[("rho_inf", 0.8)])?;
//! let mut stepper = StructuralStepper::new(method, &mut spring, 0.0, &[1.0], &[0.0])?;
//! let dt = 0.01;
//! for _ in 0..100 {
//!     let eq = stepper.step_equation(dt)?;
//!     // Start from the predictor and take one Newton step on R(q) = 0.
//!     let q = eq.q_pred[0];
//!     let a = eq.acceleration(0, q);
//!     let residual = (1.0 - eq.alpha_m) * m * a
//!         + (1.0 - eq.alpha_f) * k * q
//!         + eq.history_force[0];
//!     let k_eff = eq.mass_coefficient * m + eq.stiffness_coefficient * k;
//!     stepper.finish_step(&mut spring, dt, &[q - residual / k_eff])?;
//! }
//! // ω = 2 rad/s: q(1) ≈ cos 2, to the scheme's O(Δt²) accuracy.
//! assert!((stepper.q()[0] - 2f64.cos()).abs() < 1e-3);
//! # Ok::<(), integrate::IntegrateError>(())
//! ```
//!
//! # Other services
//! Cubic Hermite dense output over the last step ([`StructuralStepper::dense_output`], for
//! event location), restart at a new state ([`StructuralStepper::restart`]), run statistics
//! ([`crate::Stats`]), and workspaces allocated once: stepping a linear problem allocates
//! nothing (the `step_equation` convenience returns owned vectors; `step_equation_into`
//! reuses them).

mod first_order;
mod linalg;
mod linear;
mod method;
pub mod sparse;
mod step_equation;
mod stepper;
mod system;

pub use first_order::FirstOrderForm;
pub use linear::LinearStructure;
pub use method::{AlphaParameters, StructuralMethod};
pub use step_equation::StepEquation;
pub use stepper::{NewtonOptions, StructuralStepper};
pub use system::StructuralSystem;
