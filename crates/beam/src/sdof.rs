//! Exact time stepping of one modal equation under piecewise-linear forcing.
//!
//! q'' + c q' + ω² q = f(t), with f linear on each step [t_n, t_n + h]. The state (q, q') after
//! one step is an exact linear function of (q_n, q_n', f_n, f_(n+1)):
//!
//! q_(n+1)  = A11 q_n + A12 q_n' + B10 f_n + B11 f_(n+1)
//! q_(n+1)' = A21 q_n + A22 q_n' + B20 f_n + B21 f_(n+1)
//!
//! the recurrence of Nigam & Jennings (*BSSA* 59(2):909–922, 1969). Instead of their closed-form
//! coefficients (which cancel catastrophically for ω h ≪ 1 and are singular at ω = 0 or ζ = 1),
//! the coefficients are read off the exponential of the augmented matrix of the system
//! y = (q, q', f, f'), y' = [\[0,1,0,0\],[−ω²,−c,1,0],\[0,0,0,1\],\[0,0,0,0\]] y, which is exact for any
//! ω ≥ 0 and c ≥ 0 (under-, critically and over-damped, rigid modes). The exponential is computed
//! once per mode by scaling and squaring of a Taylor series on a balanced (dimensionless) matrix.

use crate::error::{BeamError, non_negative, positive};

/// Exact one-step propagator of q'' + c q' + ω² q = f(t) for piecewise-linear f.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PiecewiseLinearSdof {
    a: [[f64; 2]; 2],
    b: [[f64; 2]; 2],
}

impl PiecewiseLinearSdof {
    /// Coefficients for circular frequency `omega` ≥ 0, velocity coefficient `c` = 2ζω ≥ 0 and
    /// step `dt` > 0.
    pub fn new(omega: f64, c: f64, dt: f64) -> Result<Self, BeamError> {
        let omega = non_negative("omega", omega)?;
        let c = non_negative("damping_coefficient", c)?;
        let h = positive("dt", dt)?;
        // Balanced variables z = (s q, q', h f, h² f') with s = max(ω, 1/h): all entries of the
        // scaled generator times h are O(ωh) or O(ch) or 1.
        let s = omega.max(1.0 / h);
        let m = [
            [0.0, s * h, 0.0, 0.0],
            [-omega * omega * h / s, -c * h, 1.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
            [0.0, 0.0, 0.0, 0.0],
        ];
        let e = expm4(&m);
        // Unscale: y_i = z_i / D_i with D = (s, 1, h, h²); the slope is f' = (f1 − f0)/h.
        let q_q = e[0][0];
        let q_v = e[0][1] / s;
        let q_f = e[0][2] * h / s;
        let q_df = e[0][3] * h * h / s;
        let v_q = e[1][0] * s;
        let v_v = e[1][1];
        let v_f = e[1][2] * h;
        let v_df = e[1][3] * h * h;
        Ok(Self {
            a: [[q_q, q_v], [v_q, v_v]],
            b: [[q_f - q_df / h, q_df / h], [v_f - v_df / h, v_df / h]],
        })
    }

    /// Advance (q, q') over one step with forcing f0 at the start and f1 at the end.
    #[inline]
    pub fn step(&self, q: f64, v: f64, f0: f64, f1: f64) -> (f64, f64) {
        (
            self.a[0][0] * q + self.a[0][1] * v + self.b[0][0] * f0 + self.b[0][1] * f1,
            self.a[1][0] * q + self.a[1][1] * v + self.b[1][0] * f0 + self.b[1][1] * f1,
        )
    }
}

type M4 = [[f64; 4]; 4];

fn matmul4(a: &M4, b: &M4) -> M4 {
    let mut c = [[0.0; 4]; 4];
    for i in 0..4 {
        for k in 0..4 {
            let aik = a[i][k];
            if aik != 0.0 {
                for j in 0..4 {
                    c[i][j] += aik * b[k][j];
                }
            }
        }
    }
    c
}

/// e^M by scaling and squaring: M/2^s has 1-norm ≤ ¼, then a Taylor series to 20 terms
/// (truncation ¼²¹/21! ≈ 1e-32), then s squarings (Moler & Van Loan 2003, method 3).
fn expm4(m: &M4) -> M4 {
    let norm = (0..4)
        .map(|j| (0..4).map(|i| m[i][j].abs()).sum::<f64>())
        .fold(0.0, f64::max);
    let mut squarings = 0;
    let mut scale = 1.0;
    while norm * scale > 0.25 {
        scale *= 0.5;
        squarings += 1;
    }
    let mut x = *m;
    for row in x.iter_mut() {
        for v in row.iter_mut() {
            *v *= scale;
        }
    }
    let mut result = [[0.0; 4]; 4];
    let mut term = [[0.0; 4]; 4];
    for i in 0..4 {
        result[i][i] = 1.0;
        term[i][i] = 1.0;
    }
    for k in 1..=20 {
        term = matmul4(&term, &x);
        let inv = 1.0 / k as f64;
        for i in 0..4 {
            for j in 0..4 {
                term[i][j] *= inv;
                result[i][j] += term[i][j];
            }
        }
    }
    for _ in 0..squarings {
        result = matmul4(&result, &result);
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Undamped oscillator under a ramp f = a t from rest: q = a (t − sin(ωt)/ω)/ω² (closed form).
    /// The recurrence is exact for linear forcing, so after 1000 steps only rounding remains:
    /// tolerance 1e-12 relative to the static scale a t/ω².
    #[test]
    fn undamped_ramp_matches_closed_form() {
        let (omega, a, h) = (7.0, 3.0, 0.013);
        let p = PiecewiseLinearSdof::new(omega, 0.0, h).unwrap();
        let (mut q, mut v) = (0.0, 0.0);
        for n in 0..1000 {
            let (t0, t1) = (n as f64 * h, (n + 1) as f64 * h);
            (q, v) = p.step(q, v, a * t0, a * t1);
        }
        let t = 1000.0 * h;
        let exact = a * (t - (omega * t).sin() / omega) / (omega * omega);
        let exact_v = a * (1.0 - (omega * t).cos()) / (omega * omega);
        assert!(
            (q - exact).abs() < 1e-12 * a * t / (omega * omega),
            "{q} vs {exact}"
        );
        assert!((v - exact_v).abs() < 1e-12 * a / omega, "{v} vs {exact_v}");
    }

    /// Damped free vibration, ζ = 0.05: q = e^(−ζωt)(cos ω_d t + ζω/ω_d sin ω_d t) (closed form),
    /// tolerance 1e-12 (exact propagator, rounding over 500 steps).
    #[test]
    fn damped_free_vibration_matches_closed_form() {
        let (omega, zeta, h) = (30.0, 0.05, 1e-3);
        let p = PiecewiseLinearSdof::new(omega, 2.0 * zeta * omega, h).unwrap();
        let (mut q, mut v) = (1.0, 0.0);
        for _ in 0..500 {
            (q, v) = p.step(q, v, 0.0, 0.0);
        }
        let t = 500.0 * h;
        let wd = omega * (1.0 - zeta * zeta).sqrt();
        let exact =
            (-zeta * omega * t).exp() * ((wd * t).cos() + zeta * omega / wd * (wd * t).sin());
        assert!((q - exact).abs() < 1e-12, "{q} vs {exact}");
    }

    /// Rigid mode (ω = 0, c = 0) under f = 1 + 2t: q = t²/2 + t³/3 (exact polynomial),
    /// over-damped mode (ζ = 2) under a constant force: static limit f/ω² (checks the ζ > 1 branch
    /// that closed-form Nigam–Jennings cannot handle); tolerances 1e-12 and 1e-10 (decay e^(−ωt) of
    /// the slow root is below 1e-12 at the final time).
    #[test]
    fn rigid_and_overdamped_modes() {
        let h = 0.01;
        let p = PiecewiseLinearSdof::new(0.0, 0.0, h).unwrap();
        let (mut q, mut v) = (0.0, 0.0);
        for n in 0..300 {
            let (t0, t1) = (n as f64 * h, (n + 1) as f64 * h);
            (q, v) = p.step(q, v, 1.0 + 2.0 * t0, 1.0 + 2.0 * t1);
        }
        let t: f64 = 3.0;
        assert!(
            (q - (t * t / 2.0 + t.powi(3) / 3.0)).abs() < 1e-12 * 12.0,
            "{q}"
        );
        assert!((v - (t + t * t)).abs() < 1e-12 * 12.0, "{v}");

        let omega: f64 = 10.0;
        let p = PiecewiseLinearSdof::new(omega, 2.0 * 2.0 * omega, 0.05).unwrap();
        let (mut q, mut v) = (0.0, 0.0);
        for _ in 0..2000 {
            (q, v) = p.step(q, v, 5.0, 5.0);
        }
        assert!((q - 5.0 / (omega * omega)).abs() < 1e-10, "{q}");
        assert!(v.abs() < 1e-10);
    }

    /// Small ωh (mode 1 of a bridge at Δt = 1e-5): the coefficient B11 → h²/6 must be accurate
    /// (the closed form loses ~8 digits here); compare with the Taylor value h²/6 (1 − ω²h²/20)
    /// to 1e-12 relative.
    #[test]
    fn small_omega_h_is_accurate() {
        let (omega, h) = (30.0, 1e-5);
        let p = PiecewiseLinearSdof::new(omega, 0.0, h).unwrap();
        let exact = h * h / 6.0 * (1.0 - omega * omega * h * h / 20.0);
        assert!(
            (p.b[0][1] - exact).abs() < 1e-12 * exact,
            "{} vs {exact}",
            p.b[0][1]
        );
    }

    #[test]
    fn rejects_invalid() {
        assert!(PiecewiseLinearSdof::new(-1.0, 0.0, 0.1).is_err());
        assert!(PiecewiseLinearSdof::new(1.0, f64::NAN, 0.1).is_err());
        assert!(PiecewiseLinearSdof::new(1.0, 0.0, 0.0).is_err());
    }
}
