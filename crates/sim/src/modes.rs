//! The modal table of a bridge (`dyncontact modes`, `dyncontact.modes` in Python): n, β_n L,
//! ω_n, f_n of the mass-normalised modes, and the mode shapes sampled along the span
//! (docs/bridge.md, references.md §D1).

use beam::{BeamError, Derivative};
use serde::Serialize;

use crate::config::bridge::Bridge;

/// One mode.
#[derive(Debug, Clone, Serialize)]
pub struct ModeRow {
    /// Mode number (1-based; rigid-body modes first for a free–free beam).
    pub n: usize,
    /// Dimensionless root β_n L.
    pub beta_l: f64,
    /// Circular frequency ω_n \[rad/s\].
    pub omega: f64,
    /// Frequency f_n = ω_n/(2π) \[Hz\].
    pub frequency: f64,
}

/// The modal table (the CLI's `modes.json`).
#[derive(Debug, Clone, Serialize)]
pub struct ModesSummary {
    /// The bridge's description.
    pub bridge: String,
    /// Every mode of the basis.
    pub modes: Vec<ModeRow>,
}

/// The modal table of `b`.
pub fn summary(b: &Bridge) -> ModesSummary {
    let omegas = b.basis.circular_frequencies();
    ModesSummary {
        bridge: b.description.clone(),
        modes: (0..omegas.len())
            .map(|j| ModeRow {
                n: j + 1,
                beta_l: b.beta_l(j),
                omega: omegas[j],
                frequency: omegas[j] / (2.0 * std::f64::consts::PI),
            })
            .collect(),
    }
}

/// The mass-normalised mode shapes \[1/√kg\] at `samples` ≥ 2 equally spaced points from 0 to
/// the span length: rows `[x, w_1(x), …, w_m(x)]`.
pub fn shapes(b: &Bridge, samples: usize) -> Result<Vec<Vec<f64>>, BeamError> {
    let n = b.basis.n_modes();
    let length = b.basis.length();
    let samples = samples.max(2);
    let mut shapes = vec![0.0; n];
    let mut rows = Vec::with_capacity(samples);
    for k in 0..samples {
        let x = length * k as f64 / (samples - 1) as f64;
        b.basis.eval_all(x, Derivative::Shape, &mut shapes)?;
        let mut row = vec![x];
        row.extend_from_slice(&shapes);
        rows.push(row);
    }
    Ok(rows)
}
