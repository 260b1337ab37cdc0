//! The structural integration methods, their parameters and their selection by name.

use crate::IntegrateError;

/// A time integrator for `M q'' + C q' + f_int(q) = f_ext(t)` (references.md §D3.4–§3.5).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StructuralMethod {
    /// Störmer–Verlet in velocity form (Hairer, Lubich & Wanner 2006, §I.1.4):
    /// `v_{n+½} = v_n + ½Δt a_n`, `q_{n+1} = q_n + Δt v_{n+½}`,
    /// `(M + ½Δt C) a_{n+1} = f_ext(t_{n+1}) − f_int(q_{n+1}) − C v_{n+½}`,
    /// `v_{n+1} = v_{n+½} + ½Δt a_{n+1}`.
    /// Explicit, symplectic for `C = 0`, stable for `Ω = ωΔt < 2`. It is algebraically the
    /// central difference method (Newmark β = 0, γ = ½).
    StormerVerlet,
    /// Leapfrog, kick–drift–kick with the damping force taken at the half-step velocity:
    /// `v_{n+½} = v_n + ½Δt a_n`, `q_{n+1} = q_n + Δt v_{n+½}`,
    /// `M a_{n+1} = f_ext(t_{n+1}) − f_int(q_{n+1}) − C v_{n+½}`,
    /// `v_{n+1} = v_{n+½} + ½Δt a_{n+1}`.
    ///
    /// How it differs from [`StormerVerlet`](Self::StormerVerlet): the damping force uses the
    /// staggered velocity `v_{n+½}` (the classical choice of explicit finite-element codes), so
    /// only `M` is factorised (once, independent of Δt), at the price of first-order accuracy in
    /// the damping term. For `C = 0` both methods coincide.
    Leapfrog,
    /// Newmark-β (Newmark 1959; references.md §D3.5):
    /// `q_{n+1} = q_n + Δt v_n + Δt²[(½ − β) a_n + β a_{n+1}]`,
    /// `v_{n+1} = v_n + Δt[(1 − γ) a_n + γ a_{n+1}]`, balance at `t_{n+1}`.
    /// β = 0 makes it explicit (central difference for γ = ½).
    Newmark {
        /// β ≥ 0.
        beta: f64,
        /// γ ≥ ½ (γ < ½ has negative algorithmic damping).
        gamma: f64,
    },
    /// HHT-α (Hilber, Hughes & Taylor 1977): Newmark with `γ = (1 − 2α)/2`, `β = (1 − α)²/4` and
    /// balance `M a_{n+1} + (1 + α)(C v_{n+1} + f_int(q_{n+1})) − α(C v_n + f_int(q_n))
    /// = f_ext(t_{n+1+α})`, i.e. generalized-α with `α_m = 0`, `α_f = −α`.
    Hht {
        /// α ∈ [−1/3, 0]; ρ∞ = (1 + α)/(1 − α).
        alpha: f64,
    },
    /// Generalized-α (Chung & Hulbert 1993): `α_m = (2ρ∞ − 1)/(ρ∞ + 1)`,
    /// `α_f = ρ∞/(ρ∞ + 1)`, `γ = ½ − α_m + α_f`, `β = ¼(1 − α_m + α_f)²`.
    GeneralizedAlpha {
        /// Spectral radius at infinite frequency, ρ∞ ∈ [0, 1].
        rho_inf: f64,
    },
    /// Backward Euler for the second-order form (the baseline scheme of references.md §D4.4):
    /// `q_{n+1} = q_n + Δt v_{n+1}`, `v_{n+1} = v_n + Δt a_{n+1}`, balance at `t_{n+1}`.
    /// First order, L-stable, strongly dissipative.
    BackwardEuler,
}

impl Default for StructuralMethod {
    /// Newmark average acceleration (the trapezoidal rule).
    fn default() -> Self {
        Self::average_acceleration()
    }
}

/// The parameters of the generalized-α family (Newmark and HHT are members): β, γ and the
/// weights α_m, α_f of the step equation ([`super::StepEquation`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AlphaParameters {
    /// Newmark's β.
    pub beta: f64,
    /// Newmark's γ.
    pub gamma: f64,
    /// Inertia weight of the old acceleration.
    pub alpha_m: f64,
    /// Force weight of the old state.
    pub alpha_f: f64,
}

fn invalid(name: &'static str, reason: String) -> IntegrateError {
    IntegrateError::InvalidParameter { name, reason }
}

impl StructuralMethod {
    /// Newmark-β with the given β and γ, validated (finite, β ≥ 0, γ ≥ ½).
    pub fn newmark(beta: f64, gamma: f64) -> Result<Self, IntegrateError> {
        let method = Self::Newmark { beta, gamma };
        method.validate()?;
        Ok(method)
    }

    /// Newmark average acceleration (trapezoidal rule), β = ¼, γ = ½: second order,
    /// unconditionally stable, no algorithmic damping.
    pub fn average_acceleration() -> Self {
        Self::Newmark {
            beta: 0.25,
            gamma: 0.5,
        }
    }

    /// Newmark linear acceleration, β = 1/6, γ = ½: second order, stable for Ω < 2√3.
    pub fn linear_acceleration() -> Self {
        Self::Newmark {
            beta: 1.0 / 6.0,
            gamma: 0.5,
        }
    }

    /// Central difference as the Newmark variant β = 0, γ = ½: explicit, stable for Ω < 2.
    pub fn central_difference() -> Self {
        Self::Newmark {
            beta: 0.0,
            gamma: 0.5,
        }
    }

    /// HHT-α, validated (α ∈ [−1/3, 0]).
    pub fn hht(alpha: f64) -> Result<Self, IntegrateError> {
        let method = Self::Hht { alpha };
        method.validate()?;
        Ok(method)
    }

    /// Generalized-α by its high-frequency spectral radius, validated (ρ∞ ∈ [0, 1]).
    pub fn generalized_alpha(rho_inf: f64) -> Result<Self, IntegrateError> {
        let method = Self::GeneralizedAlpha { rho_inf };
        method.validate()?;
        Ok(method)
    }

    /// Selects a method by name with named parameters, for a command line or a scenario file.
    ///
    /// Names (case-insensitive, `-` and `_` equivalent):
    /// `newmark` (`beta` = 0.25, `gamma` = 0.5 by default), `average_acceleration`,
    /// `linear_acceleration`, `central_difference`, `hht` (`alpha`, default −0.1),
    /// `generalized_alpha` (`rho_inf`, default 0.8), `verlet` (`stormer_verlet`),
    /// `leapfrog`, `backward_euler`. An unknown name or parameter is an error.
    pub fn by_name(name: &str, parameters: &[(&str, f64)]) -> Result<Self, IntegrateError> {
        let key = name.trim().to_ascii_lowercase().replace('-', "_");
        let (allowed, method): (&[&str], MethodBuilder) = match key.as_str() {
            "newmark" => (&["beta", "gamma"], |p| {
                Self::newmark(p.get("beta", 0.25), p.get("gamma", 0.5))
            }),
            "average_acceleration" | "trapezoidal" => (&[], |_| Ok(Self::average_acceleration())),
            "linear_acceleration" => (&[], |_| Ok(Self::linear_acceleration())),
            "central_difference" => (&[], |_| Ok(Self::central_difference())),
            "hht" | "hht_alpha" => (&["alpha"], |p| Self::hht(p.get("alpha", -0.1))),
            "generalized_alpha" | "generalised_alpha" | "gen_alpha" => (&["rho_inf"], |p| {
                Self::generalized_alpha(p.get("rho_inf", 0.8))
            }),
            "verlet" | "stormer_verlet" | "velocity_verlet" => (&[], |_| Ok(Self::StormerVerlet)),
            "leapfrog" => (&[], |_| Ok(Self::Leapfrog)),
            "backward_euler" => (&[], |_| Ok(Self::BackwardEuler)),
            _ => {
                return Err(invalid(
                    "method",
                    format!(
                        "unknown structural method `{name}` (known: newmark, average_acceleration \
                         or trapezoidal, linear_acceleration, central_difference, hht, \
                         generalized_alpha, verlet, leapfrog, backward_euler)"
                    ),
                ));
            }
        };
        if let Some((p, _)) = parameters.iter().find(|(p, _)| !allowed.contains(p)) {
            return Err(invalid(
                "parameter",
                format!("`{p}` is not a parameter of `{key}` (allowed: {allowed:?})"),
            ));
        }
        method(&Params(parameters))
    }

    /// Checks the parameters (used by the constructors and by the stepper).
    pub fn validate(&self) -> Result<(), IntegrateError> {
        match *self {
            Self::Newmark { beta, gamma } => {
                if !(beta.is_finite() && beta >= 0.0) {
                    return Err(invalid(
                        "beta",
                        format!("β = {beta} (must be finite and ≥ 0)"),
                    ));
                }
                if !(gamma.is_finite() && gamma >= 0.5) {
                    return Err(invalid(
                        "gamma",
                        format!("γ = {gamma} (must be finite and ≥ 1/2; γ < 1/2 is unstable)"),
                    ));
                }
            }
            Self::Hht { alpha } => {
                if !(alpha.is_finite() && (-1.0 / 3.0..=0.0).contains(&alpha)) {
                    return Err(invalid(
                        "alpha",
                        format!("α = {alpha} (must lie in [−1/3, 0])"),
                    ));
                }
            }
            Self::GeneralizedAlpha { rho_inf } => {
                if !(rho_inf.is_finite() && (0.0..=1.0).contains(&rho_inf)) {
                    return Err(invalid(
                        "rho_inf",
                        format!("ρ∞ = {rho_inf} (must lie in [0, 1])"),
                    ));
                }
            }
            Self::StormerVerlet | Self::Leapfrog | Self::BackwardEuler => {}
        }
        Ok(())
    }

    /// Short name, as accepted by [`by_name`](Self::by_name).
    pub fn name(&self) -> &'static str {
        match self {
            Self::StormerVerlet => "verlet",
            Self::Leapfrog => "leapfrog",
            Self::Newmark { beta, .. } if *beta == 0.0 => "central_difference",
            Self::Newmark { .. } => "newmark",
            Self::Hht { .. } => "hht",
            Self::GeneralizedAlpha { .. } => "generalized_alpha",
            Self::BackwardEuler => "backward_euler",
        }
    }

    /// The largest stable step for an undamped mode of circular frequency `omega_max`
    /// \[rad/s\], or `None` for an unconditionally stable method. Linear stability of the
    /// Newmark family (Hughes 2000, *The Finite Element Method* §9.1; references.md §D3.5):
    /// with γ ≥ ½ the scheme is unconditionally stable for 2β ≥ γ, otherwise stable for
    /// `Ω = ω Δt ≤ Ω_crit = 1/√(γ/2 − β)`, which is 2 for central difference (β = 0, γ = ½).
    /// Störmer–Verlet and leapfrog are central difference in another form: `Δt ≤ 2/ω`.
    /// HHT-α, generalized-α and backward Euler are unconditionally stable. Damping only
    /// lowers the limit of the half-step-damped leapfrog slightly; the undamped limit is the
    /// one checked.
    pub fn critical_step(&self, omega_max: f64) -> Option<f64> {
        let omega_crit = match *self {
            Self::StormerVerlet | Self::Leapfrog => 2.0,
            Self::Newmark { beta, gamma } if 2.0 * beta < gamma => {
                1.0 / (0.5 * gamma - beta).sqrt()
            }
            _ => return None,
        };
        Some(omega_crit / omega_max)
    }

    /// `true` for the explicit methods (Verlet, leapfrog, Newmark with β = 0): they have no
    /// nonlinear step equation.
    pub fn is_explicit(&self) -> bool {
        match self {
            Self::StormerVerlet | Self::Leapfrog => true,
            Self::Newmark { beta, .. } => *beta == 0.0,
            _ => false,
        }
    }

    /// Parameters in the generalized-α form, or `None` for Verlet, leapfrog, backward Euler.
    pub fn alpha_parameters(&self) -> Option<AlphaParameters> {
        match *self {
            Self::Newmark { beta, gamma } => Some(AlphaParameters {
                beta,
                gamma,
                alpha_m: 0.0,
                alpha_f: 0.0,
            }),
            Self::Hht { alpha } => Some(AlphaParameters {
                beta: (1.0 - alpha).powi(2) / 4.0,
                gamma: (1.0 - 2.0 * alpha) / 2.0,
                alpha_m: 0.0,
                alpha_f: -alpha,
            }),
            Self::GeneralizedAlpha { rho_inf } => {
                let alpha_m = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0);
                let alpha_f = rho_inf / (rho_inf + 1.0);
                let gamma = 0.5 - alpha_m + alpha_f;
                let beta = 0.25 * (1.0 - alpha_m + alpha_f).powi(2);
                Some(AlphaParameters {
                    beta,
                    gamma,
                    alpha_m,
                    alpha_f,
                })
            }
            Self::StormerVerlet | Self::Leapfrog | Self::BackwardEuler => None,
        }
    }
}

/// Builds a method from its named parameters.
type MethodBuilder = fn(&Params) -> Result<StructuralMethod, IntegrateError>;

/// Named parameters given to [`StructuralMethod::by_name`].
struct Params<'a>(&'a [(&'a str, f64)]);

impl Params<'_> {
    fn get(&self, key: &str, default: f64) -> f64 {
        self.0
            .iter()
            .rev()
            .find(|(k, _)| *k == key)
            .map_or(default, |(_, v)| *v)
    }
}
