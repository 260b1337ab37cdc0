//! Closed-form response of a simply supported beam to a moving constant force
//! (references.md §D1.1; Frýba 1999 ch. 1; Olsson 1991), undamped.
//!
//! w(x,t) = (2PL³/(π⁴EI)) Σ_j T_j(t) sin(jπx/L) with, for 0 ≤ t ≤ L/c,
//! T_j(t) = [sin(jΩt) − (α/j) sin(ω_j t)] / (j²(j² − α²)), Ω = πc/L, ω_j = j²ω₁, α = Ω/ω₁.
//! The term is evaluated in the resonance-safe form (exact rewriting with sin a − sin b =
//! 2 cos((a+b)/2) sin((a−b)/2)):
//! T_j = [sin(ω_j t)/j − jω₁t cos(m) sinc(d)] / (j²(j + α)), m = (jΩ + ω_j)t/2, d = (jΩ − ω_j)t/2,
//! which is continuous through α = j (no 0/0; at α = 1 it gives ½(sin ω₁t − ω₁t cos ω₁t)).
//! After the force leaves (t > L/c) each mode vibrates freely from its state at L/c.

use std::f64::consts::PI;

use crate::analytic::UniformBeam;
use crate::error::{BeamError, finite, non_negative, positive};

/// A constant force P moving at speed c over a simply supported uniform beam.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SsMovingForce {
    beam: UniformBeam,
    force: f64,
    speed: f64,
}

/// Static midspan deflection of a simply supported beam under a midspan point force:
/// δ_st = F L³ / (48 EI).
pub fn ss_midspan_static_deflection(force: f64, length: f64, bending_stiffness: f64) -> f64 {
    force * length.powi(3) / (48.0 * bending_stiffness)
}

/// ω₁ of the simply supported beam: (π/L)² √(EI/ρA).
fn omega_1(beam: &UniformBeam) -> f64 {
    (PI / beam.length).powi(2) * (beam.bending_stiffness / beam.mass_per_length).sqrt()
}

/// Speed c = 2 f₁ L α giving the speed parameter α (critical speed at α = 1).
pub fn speed_for_parameter(beam: &UniformBeam, alpha: f64) -> Result<f64, BeamError> {
    let alpha = positive("alpha", alpha)?;
    Ok(alpha * omega_1(beam) * beam.length / PI)
}

impl SsMovingForce {
    /// Validate the force (finite) and speed (> 0).
    pub fn new(beam: UniformBeam, force: f64, speed: f64) -> Result<Self, BeamError> {
        let beam = UniformBeam::new(beam.length, beam.bending_stiffness, beam.mass_per_length)?;
        Ok(Self {
            beam,
            force: finite("force", force)?,
            speed: positive("speed", speed)?,
        })
    }

    /// Speed parameter α = Ω/ω₁ = πc/(L ω₁).
    pub fn speed_parameter(&self) -> f64 {
        PI * self.speed / (self.beam.length * omega_1(&self.beam))
    }

    /// Time L/c at which the force leaves the span.
    pub fn exit_time(&self) -> f64 {
        self.beam.length / self.speed
    }

    /// Forced-phase modal amplitude T_j(t) and its rate dT_j/dt (resonance-safe form).
    fn forced_term(&self, j: usize, t: f64) -> (f64, f64) {
        let jf = j as f64;
        let w1 = omega_1(&self.beam);
        let alpha = self.speed_parameter();
        let a = jf * alpha * w1 * t;
        let b = jf * jf * w1 * t;
        let (m, d) = (0.5 * (a + b), 0.5 * (a - b));
        let sinc = if d == 0.0 { 1.0 } else { d.sin() / d };
        let value = (b.sin() / jf - jf * w1 * t * m.cos() * sinc) / (jf * jf * (jf + alpha));
        // dT/dt = α ω₁² t sin(m) sinc(d) / (j + α) (same rewriting of cos a − cos b).
        let rate = alpha * w1 * w1 * t * m.sin() * sinc / (jf + alpha);
        (value, rate)
    }

    /// Series deflection w(x, t) \[m\] with `n_terms` modes, for any t ≥ 0.
    pub fn deflection(&self, x: f64, t: f64, n_terms: usize) -> Result<f64, BeamError> {
        crate::error::inside_span("x", x, self.beam.length)?;
        non_negative("t", t)?;
        if n_terms == 0 {
            return Err(BeamError::InvalidCount {
                name: "n_terms",
                value: 0,
                reason: "at least one term",
            });
        }
        let l = self.beam.length;
        let scale = 2.0 * self.force * l.powi(3) / (PI.powi(4) * self.beam.bending_stiffness);
        let w1 = omega_1(&self.beam);
        let exit = self.exit_time();
        let mut sum = 0.0;
        for j in 1..=n_terms {
            let jf = j as f64;
            let amplitude = if t <= exit {
                self.forced_term(j, t).0
            } else {
                let (value, rate) = self.forced_term(j, exit);
                let wj = jf * jf * w1;
                let tau = t - exit;
                value * (wj * tau).cos() + rate / wj * (wj * tau).sin()
            };
            sum += amplitude * (jf * PI * x / l).sin();
        }
        Ok(scale * sum)
    }
}
