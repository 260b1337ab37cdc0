//! The structural-method parameters of an `[integrator]` section (β, γ of Newmark, α of HHT,
//! ρ∞ of the generalized-α method), shared by every scenario kind.

use serde::Deserialize;

use super::ConfigError;
use integrate::structural::StructuralMethod;

/// The optional parameter keys of the structural methods, as written in `[integrator]`.
#[derive(Debug, Clone, Copy, Default, Deserialize, PartialEq)]
pub struct StructuralParameters {
    /// Newmark β.
    pub beta: Option<f64>,
    /// Newmark γ.
    pub gamma: Option<f64>,
    /// HHT α (−⅓ ≤ α ≤ 0).
    pub alpha: Option<f64>,
    /// Generalized-α spectral radius at infinite frequency ρ∞ ∈ \[0, 1\].
    pub rho_inf: Option<f64>,
}

impl StructuralParameters {
    /// The keys that are set, in the order beta, gamma, alpha, rho_inf, as the
    /// `(name, value)` list of [`StructuralMethod::by_name`]; each must be finite.
    pub fn list(&self) -> Result<Vec<(&'static str, f64)>, ConfigError> {
        let mut params = Vec::new();
        for (key, value) in [
            ("beta", self.beta),
            ("gamma", self.gamma),
            ("alpha", self.alpha),
            ("rho_inf", self.rho_inf),
        ] {
            if let Some(v) = value {
                if !v.is_finite() {
                    bail!("`integrator.{key}` = {v}: must be a finite number");
                }
                params.push((key, v));
            }
        }
        Ok(params)
    }

    /// The structural method `name` with these parameters; the error names the key.
    pub fn method(&self, name: &str) -> Result<StructuralMethod, ConfigError> {
        let params = self.list()?;
        StructuralMethod::by_name(name, &params)
            .map_err(|e| invalid!("[integrator] `method` = \"{name}\": {e}"))
    }
}
