//! Quadrature rules on an interval: composite Gauss–Legendre and composite Simpson
//! (the closed Newton–Cotes rule of references.md §D4.4).

use crate::error::{BeamError, finite};

/// Which composite rule to build.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum QuadratureRule {
    /// `panels` equal panels, each with an n-point Gauss–Legendre rule (exact for polynomials of
    /// degree 2n − 1 on each panel).
    GaussLegendre {
        /// Points per panel (1 ..= 64).
        points: usize,
        /// Number of equal panels (≥ 1).
        panels: usize,
    },
    /// Composite Simpson rule with an even number of equal intervals (error O(h⁴)).
    Simpson {
        /// Number of intervals (even, ≥ 2).
        intervals: usize,
    },
}

/// Nodes and weights of a quadrature rule on [a, b]: ∫ f ≈ Σ w_k f(x_k).
#[derive(Debug, Clone, PartialEq)]
pub struct Quadrature {
    nodes: Vec<f64>,
    weights: Vec<f64>,
}

/// Gauss–Legendre nodes and weights on [−1, 1].
///
/// Newton iteration on P_n from the Tricomi initial guess cos(π(i − ¼)/(n + ½)), with the
/// three-term recurrence k P_k = (2k − 1) x P_(k−1) − (k − 1) P_(k−2),
/// P_n' = n (x P_n − P_(n−1)) / (x² − 1) and weights w_i = 2 / ((1 − x_i²) P_n'(x_i)²)
/// (Abramowitz & Stegun 25.4.29).
pub fn gauss_legendre(n: usize) -> Result<(Vec<f64>, Vec<f64>), BeamError> {
    if n == 0 || n > 64 {
        return Err(BeamError::InvalidCount {
            name: "points",
            value: n,
            reason: "Gauss-Legendre rules are provided for 1..=64 points",
        });
    }
    let mut x = vec![0.0; n];
    let mut w = vec![0.0; n];
    let nf = n as f64;
    for i in 0..n.div_ceil(2) {
        let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (nf + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (p, p_prev) = legendre_pair(n, z);
            dp = nf * (z * p - p_prev) / (z * z - 1.0);
            let dz = p / dp;
            z -= dz;
            if dz.abs() <= 4.0 * f64::EPSILON {
                let (p, p_prev) = legendre_pair(n, z);
                dp = nf * (z * p - p_prev) / (z * z - 1.0);
                break;
            }
        }
        let wi = 2.0 / ((1.0 - z * z) * dp * dp);
        x[i] = -z;
        x[n - 1 - i] = z;
        w[i] = wi;
        w[n - 1 - i] = wi;
    }
    if n % 2 == 1 {
        x[n / 2] = 0.0;
    }
    Ok((x, w))
}

/// (P_n(z), P_(n−1)(z)) by the three-term recurrence.
fn legendre_pair(n: usize, z: f64) -> (f64, f64) {
    let (mut p_prev, mut p) = (1.0, z);
    if n == 0 {
        return (1.0, 0.0);
    }
    for k in 2..=n {
        let kf = k as f64;
        let next = ((2.0 * kf - 1.0) * z * p - (kf - 1.0) * p_prev) / kf;
        p_prev = p;
        p = next;
    }
    (p, p_prev)
}

impl Quadrature {
    /// Build `rule` on [a, b] (a < b, finite).
    pub fn new(rule: QuadratureRule, a: f64, b: f64) -> Result<Self, BeamError> {
        finite("a", a)?;
        finite("b", b)?;
        if b <= a {
            return Err(BeamError::InvalidParameter {
                name: "b",
                value: b,
                reason: "interval end must exceed its start",
            });
        }
        match rule {
            QuadratureRule::GaussLegendre { points, panels } => Self::gauss(points, panels, a, b),
            QuadratureRule::Simpson { intervals } => Self::simpson(intervals, a, b),
        }
    }

    fn gauss(points: usize, panels: usize, a: f64, b: f64) -> Result<Self, BeamError> {
        if panels == 0 {
            return Err(BeamError::InvalidCount {
                name: "panels",
                value: 0,
                reason: "at least one panel",
            });
        }
        let (xg, wg) = gauss_legendre(points)?;
        let h = (b - a) / panels as f64;
        let mut nodes = Vec::with_capacity(points * panels);
        let mut weights = Vec::with_capacity(points * panels);
        for p in 0..panels {
            let mid = a + (p as f64 + 0.5) * h;
            for (x, w) in xg.iter().zip(&wg) {
                nodes.push(mid + 0.5 * h * x);
                weights.push(0.5 * h * w);
            }
        }
        Ok(Self { nodes, weights })
    }

    /// Composite Simpson: h/3 (f_0 + 4 f_1 + 2 f_2 + … + 4 f_(n−1) + f_n).
    fn simpson(intervals: usize, a: f64, b: f64) -> Result<Self, BeamError> {
        if intervals < 2 || intervals % 2 == 1 {
            return Err(BeamError::InvalidCount {
                name: "intervals",
                value: intervals,
                reason: "Simpson needs an even number >= 2",
            });
        }
        let h = (b - a) / intervals as f64;
        let nodes = (0..=intervals).map(|i| a + i as f64 * h).collect();
        let weights = (0..=intervals)
            .map(|i| {
                let c = if i == 0 || i == intervals {
                    1.0
                } else if i % 2 == 1 {
                    4.0
                } else {
                    2.0
                };
                c * h / 3.0
            })
            .collect();
        Ok(Self { nodes, weights })
    }

    /// Quadrature nodes x_k.
    pub fn nodes(&self) -> &[f64] {
        &self.nodes
    }

    /// Quadrature weights w_k.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// Σ w_k f(x_k).
    pub fn integrate(&self, f: impl Fn(f64) -> f64) -> f64 {
        self.nodes
            .iter()
            .zip(&self.weights)
            .map(|(&x, &w)| w * f(x))
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Gauss–Legendre with n points integrates x^(2n−1) and x^(2n−2) exactly: compare with the
    /// closed form ∫_0^1 x^k = 1/(k + 1); tolerance 1e-14 (rounding of the nodes).
    #[test]
    fn gauss_is_exact_to_degree_2n_minus_1() {
        for n in [1, 2, 5, 10, 20, 40, 64] {
            let q = Quadrature::new(
                QuadratureRule::GaussLegendre {
                    points: n,
                    panels: 1,
                },
                0.0,
                1.0,
            )
            .unwrap();
            for k in [2 * n - 2, 2 * n - 1] {
                let exact = 1.0 / (k as f64 + 1.0);
                let got = q.integrate(|x| x.powi(k as i32));
                assert!((got - exact).abs() < 1e-14, "n={n} k={k}: {got} vs {exact}");
            }
            // The rule is not exact at degree 2n (sanity that the test can fail); for n > 10 the
            // degree-2n error on [0, 1] is itself below rounding, so check small n only.
            if n <= 10 {
                let k = 2 * n;
                let err = (q.integrate(|x| x.powi(k as i32)) - 1.0 / (k as f64 + 1.0)).abs();
                assert!(err > 1e-12, "n={n} degree 2n unexpectedly exact: {err}");
            }
        }
    }

    /// Composite Simpson on ∫_0^π sin = 2: observed order log2(e_h/e_(h/2)) must be 4 ± 0.1.
    #[test]
    fn simpson_converges_at_fourth_order() {
        let err = |n: usize| {
            let q = Quadrature::new(
                QuadratureRule::Simpson { intervals: n },
                0.0,
                std::f64::consts::PI,
            )
            .unwrap();
            (q.integrate(f64::sin) - 2.0).abs()
        };
        let order = (err(16) / err(32)).log2();
        assert!((order - 4.0).abs() < 0.1, "Simpson order {order}");
    }

    #[test]
    fn rejects_bad_rules() {
        assert!(Quadrature::new(QuadratureRule::Simpson { intervals: 3 }, 0.0, 1.0).is_err());
        assert!(
            Quadrature::new(
                QuadratureRule::GaussLegendre {
                    points: 0,
                    panels: 1
                },
                0.0,
                1.0
            )
            .is_err()
        );
        assert!(
            Quadrature::new(
                QuadratureRule::GaussLegendre {
                    points: 3,
                    panels: 2
                },
                1.0,
                0.0
            )
            .is_err()
        );
        assert!(Quadrature::new(QuadratureRule::Simpson { intervals: 4 }, f64::NAN, 1.0).is_err());
    }
}
