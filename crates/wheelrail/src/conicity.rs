//! Equivalent conicity from the rolling radius difference Δr(y) (references.md §W2.3).
//!
//! For a sinusoidal lateral motion y = A sin ψ, the equivalent conicity is the first
//! harmonic of Δr over the motion, λ_e(A) = (1/(2A))·(1/π)∫₀^{2π} Δr(A sin ψ) sin ψ dψ
//! (harmonic linearisation, one of the methods EN 15302 admits; Δr = 2λy gives λ_e = λ).
//! The integral is a periodic trapezoidal sum at ψ_k = 2π(k + ½)/n.

use crate::error::{WheelRailError, in_range};
use crate::wheelset::{Roll, Wheelset};

/// Equivalent conicity at amplitude `amplitude` \[m\] from `nodes` evaluations of Δr.
pub fn equivalent_conicity(
    wheelset: &Wheelset,
    amplitude: f64,
    nodes: usize,
) -> Result<f64, WheelRailError> {
    in_range(
        "amplitude",
        amplitude,
        1e-5,
        0.02,
        "must lie in [1e-5, 0.02] m",
    )?;
    in_range("nodes", nodes as f64, 8.0, 4096.0, "must lie in [8, 4096]")?;
    let mut sum = 0.0;
    for k in 0..nodes {
        let psi = 2.0 * std::f64::consts::PI * (k as f64 + 0.5) / nodes as f64;
        let c = wheelset.contact(amplitude * psi.sin(), Roll::Equilibrium)?;
        sum += c.delta_r() * psi.sin();
    }
    Ok(sum * 2.0 / nodes as f64 / (2.0 * amplitude))
}
