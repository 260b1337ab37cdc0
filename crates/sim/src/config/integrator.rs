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

    /// The structural method `name` with these parameters; the error names the key. An
    /// unknown name also lists `also`, the other methods the scenario kind takes (`exact`,
    /// `radau5`), and suggests the nearest known name.
    pub fn method(&self, name: &str, also: &[&str]) -> Result<StructuralMethod, ConfigError> {
        let params = self.list()?;
        StructuralMethod::by_name(name, &params).map_err(|e| {
            let mut m = format!("[integrator] `method` = \"{name}\": {e}");
            if e.to_string().contains("unknown structural method") {
                if !also.is_empty() {
                    m.push_str(&format!("; this kind also takes {}", also.join(", ")));
                }
                let known: Vec<&str> = STRUCTURAL_NAMES.iter().chain(also).copied().collect();
                m.push_str(&super::suggestion(name.trim(), &known));
            }
            invalid!("{m}")
        })
    }
}

/// The structural methods' names as a scenario file writes them (for suggestions).
const STRUCTURAL_NAMES: [&str; 10] = [
    "newmark",
    "average_acceleration",
    "trapezoidal",
    "linear_acceleration",
    "central_difference",
    "hht",
    "generalized_alpha",
    "verlet",
    "leapfrog",
    "backward_euler",
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_unknown_method_lists_the_other_methods_and_the_nearest() {
        let p = StructuralParameters::default();
        let e = p.method("radau", &["radau5"]).unwrap_err().to_string();
        assert!(
            e.contains("unknown structural method")
                && e.contains("this kind also takes radau5")
                && e.ends_with("(did you mean `radau5`?)"),
            "{e}"
        );
        let e = p
            .method("generalized_alfa", &["exact"])
            .unwrap_err()
            .to_string();
        assert!(e.ends_with("(did you mean `generalized_alpha`?)"), "{e}");
        assert!(p.method("newmark", &[]).is_ok());
    }
}
