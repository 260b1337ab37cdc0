//! Time integrators for dyncontact.
//!
//! Two problem families, separated from the methods that solve them (after diffsol's design):
//!
//! * first-order systems `y' = f(t, y)` ([`ode`]): explicit Euler, RK4, Dormand–Prince 5(4),
//!   backward Euler, Radau IIA (order 5), variable-order BDF, Adams–Bashforth–Moulton;
//! * second-order structural systems `M q'' + C q' + f_int(q) = f_ext(t)` ([`structural`]):
//!   Störmer–Verlet, leapfrog, Newmark-β, HHT-α, generalized-α.
//!
//! Every method is driven step by step (initialise, step, read the state), so an outer
//! simulation (the vehicle–bridge coupling) can interleave its own work between steps and,
//! for the implicit structural schemes, solve the step equation with its own nonlinear solver.

pub mod error;
mod lu;
pub mod ode;
pub mod root;
pub mod stats;
pub mod structural;

pub use error::{CallbackError, IntegrateError};
pub use ode::{Method, OdeOptions, OdeStepper, OdeSystem};
pub use root::{Root, illinois};
pub use stats::Stats;
pub use structural::{
    FirstOrderForm, LinearStructure, NewtonOptions, StepEquation, StructuralMethod,
    StructuralStepper, StructuralSystem,
};
