//! The tangential method and the one rule that chooses a coupled or a sequential solve.
//!
//! With K ≠ 0 (dissimilar materials, [`crate::Material::k`]) the normal pressure and the
//! tangential tractions displace each other (references.md §C3.1–3.2); only the exact
//! half-space method can represent that coupling, by the normal–tangential outer loop of
//! [`crate::solve_coupled`] (Panagiotopoulos' process). Every other case — K = 0 (one pass is
//! exact, Johnson's process) or a simplified theory (FASTSIM, linear theory, which assume
//! K = 0 on the Hertz ellipse) — solves the normal problem first and then the tangential one.
//! `contact`, `creep-curve` and the vehicle–bridge traction all ask [`tangential_strategy`].

use crate::material::Material;

/// How the tangential problem is solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TangentialMethod {
    /// The half-space solver (ConvexGS/SteadyGS, references.md §C3.5; steady rolling by
    /// Newton–Krylov, §C3.9).
    Exact,
    /// Kalker's FASTSIM on the Hertz ellipse (references.md §C4.3).
    Fastsim,
    /// Kalker's linear theory on the Hertz ellipse (references.md §C4.2).
    Linear,
}

impl TangentialMethod {
    /// `exact`, `fastsim` or `linear` (case-insensitive, surrounding blanks ignored).
    pub fn by_name(name: &str) -> Option<Self> {
        match name.trim().to_ascii_lowercase().as_str() {
            "exact" => Some(Self::Exact),
            "fastsim" => Some(Self::Fastsim),
            "linear" => Some(Self::Linear),
            _ => None,
        }
    }

    /// The scenario-file name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Exact => "exact",
            Self::Fastsim => "fastsim",
            Self::Linear => "linear",
        }
    }
}

/// Coupled (outer loop) or sequential (normal, then tangential) solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TangentialStrategy {
    /// Normal–tangential outer loop ([`crate::solve_coupled`], [`crate::solve_coupled_step`]).
    Coupled,
    /// One normal solve, then one tangential solve on its pressure.
    Sequential,
}

/// The strategy for `method` with `material`: [`TangentialStrategy::Coupled`] exactly when the
/// method is [`TangentialMethod::Exact`] and K ≠ 0 (module documentation).
pub fn tangential_strategy(method: TangentialMethod, material: &Material) -> TangentialStrategy {
    if method == TangentialMethod::Exact && material.k != 0.0 {
        TangentialStrategy::Coupled
    } else {
        TangentialStrategy::Sequential
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::{Body, Material};

    #[test]
    fn coupled_only_for_exact_with_dissimilar_materials() {
        let same = Material::identical(210e9, 0.3).unwrap();
        let steel_on_rubber = Material::combine(
            Body::elastic(210e9, 0.3).unwrap(),
            Body::elastic(10e6, 0.45).unwrap(),
        )
        .unwrap();
        assert_eq!(same.k, 0.0);
        assert!(steel_on_rubber.k != 0.0);
        use TangentialMethod::*;
        use TangentialStrategy::*;
        assert_eq!(tangential_strategy(Exact, &same), Sequential);
        assert_eq!(tangential_strategy(Exact, &steel_on_rubber), Coupled);
        assert_eq!(tangential_strategy(Fastsim, &steel_on_rubber), Sequential);
        assert_eq!(tangential_strategy(Linear, &steel_on_rubber), Sequential);
        for m in [Exact, Fastsim, Linear] {
            assert_eq!(
                TangentialMethod::by_name(&format!(" {} ", m.name().to_uppercase())),
                Some(m)
            );
        }
        assert_eq!(TangentialMethod::by_name("kalker"), None);
    }
}
