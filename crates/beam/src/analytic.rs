//! Analytic Euler–Bernoulli modes of uniform beams (references.md §D1.6).
//!
//! Frequencies ω_n = (β_n L)² √(EI / (ρA L⁴)). The roots β_n L of the characteristic equations are
//! found by a bracketed, safeguarded Newton iteration on overflow-free forms of the equations and,
//! beyond the index where the exponentially small correction drops below double precision, taken
//! from the asymptotic formulas of references.md §D1.6. Mode shapes use the stable rewrite of §1.6
//! (Gonçalves, Brennan & Elliott 2007), which contains no large hyperbolic functions, and its
//! analytic derivatives; they are mass-normalised, ∫ ρA w_i w_j dx = δ_ij.

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

use crate::error::{
    BENDING_STIFFNESS_RANGE, BeamError, LENGTH_RANGE, MASS_PER_LENGTH_RANGE, MAX_MODES, check_size,
    in_range, inside_span, positive,
};
use crate::modal::{Derivative, ModalBasis, check_len, check_mode};

/// Boundary conditions of a single-span uniform beam (left end first).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Support {
    /// Pinned–pinned: w = w'' = 0 at both ends; φ_n = sin(nπx/L), β_n L = nπ.
    SimplySupported,
    /// Clamped–clamped: w = w' = 0 at both ends; cos βL cosh βL = 1.
    ClampedClamped,
    /// Cantilever, clamped at x = 0 and free at x = L; cos βL cosh βL = −1.
    ClampedFree,
    /// Clamped at x = 0, pinned at x = L; tan βL = tanh βL.
    ClampedPinned,
    /// Free–free: two rigid-body modes (translation, rotation) then cos βL cosh βL = 1.
    FreeFree,
}

impl Support {
    /// Number of rigid-body (zero-frequency) modes: 2 for free–free, else 0.
    pub fn rigid_modes(self) -> usize {
        match self {
            Support::FreeFree => 2,
            _ => 0,
        }
    }
}

/// Index from which the asymptotic root is exact in double precision (references.md §D1.6: the
/// correction underflows relative to βL for n ≥ 12 (CC, FF, cantilever) and n ≥ 6 (CP)).
fn asymptotic_from(support: Support) -> usize {
    match support {
        Support::ClampedPinned => 6,
        _ => 12,
    }
}

/// Leading asymptotic term g_n of the n-th elastic root (n ≥ 1).
fn leading_term(support: Support, n: usize) -> f64 {
    let n = n as f64;
    match support {
        Support::SimplySupported => n * PI,
        Support::ClampedClamped | Support::FreeFree => (2.0 * n + 1.0) * FRAC_PI_2,
        Support::ClampedFree => (2.0 * n - 1.0) * FRAC_PI_2,
        Support::ClampedPinned => (4.0 * n + 1.0) * FRAC_PI_4,
    }
}

/// Asymptotic root (references.md §D1.6):
/// CC/FF and cantilever β_nL ≈ g_n + (−1)^(n+1) 2 e^(−g_n); clamped–pinned β_nL ≈ g_n − e^(−2 g_n).
pub fn asymptotic_root(support: Support, n: usize) -> f64 {
    let g = leading_term(support, n);
    let sign = if n % 2 == 1 { 1.0 } else { -1.0 };
    match support {
        Support::SimplySupported => g,
        Support::ClampedClamped | Support::FreeFree | Support::ClampedFree => {
            g + sign * 2.0 * (-g).exp()
        }
        Support::ClampedPinned => g - (-2.0 * g).exp(),
    }
}

/// Overflow-free characteristic function and its derivative at β:
/// CC/FF cos β − sech β; cantilever cos β + sech β; CP sin β − cos β tanh β (= cos β (tan β − tanh β)).
fn characteristic(support: Support, b: f64) -> (f64, f64) {
    let (s, c) = b.sin_cos();
    let sech = 1.0 / b.cosh();
    let th = b.tanh();
    match support {
        Support::SimplySupported => (s, c),
        Support::ClampedClamped | Support::FreeFree => (c - sech, -s + sech * th),
        Support::ClampedFree => (c + sech, -s - sech * th),
        Support::ClampedPinned => (s - c * th, c + s * th - c * sech * sech),
    }
}

/// The n-th (1-based) elastic root β_n L of the characteristic equation of `support`.
///
/// Bracket [g_n − 0.5, g_n + 0.5] around the leading term (roots are π apart, so the bracket holds
/// exactly one), then Newton steps safeguarded by bisection until the bracket is a few ulp wide.
/// For n beyond the threshold of references.md §D1.6 the asymptotic formula is returned directly.
pub fn characteristic_root(support: Support, n: usize) -> Result<f64, BeamError> {
    if n == 0 {
        return Err(BeamError::InvalidCount {
            name: "n",
            value: n,
            reason: "elastic mode numbers start at 1",
        });
    }
    if support == Support::SimplySupported {
        return Ok(n as f64 * PI);
    }
    if n >= asymptotic_from(support) {
        return Ok(asymptotic_root(support, n));
    }
    let g = leading_term(support, n);
    let (mut lo, mut hi) = (g - 0.5, g + 0.5);
    let (flo, fhi) = (characteristic(support, lo).0, characteristic(support, hi).0);
    if flo * fhi > 0.0 {
        return Err(BeamError::RootNotBracketed { n, lo, hi });
    }
    let lo_negative = flo < 0.0;
    let mut x = asymptotic_root(support, n).clamp(lo, hi);
    for _ in 0..200 {
        let (f, df) = characteristic(support, x);
        if f == 0.0 {
            return Ok(x);
        }
        if (f < 0.0) == lo_negative {
            lo = x;
        } else {
            hi = x;
        }
        let newton = x - f / df;
        let next = if newton > lo && newton < hi && df != 0.0 {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if (next - x).abs() <= 2.0 * f64::EPSILON * x || hi - lo <= 4.0 * f64::EPSILON * x {
            return Ok(next);
        }
        x = next;
    }
    Ok(x)
}

/// Validated properties of a uniform beam.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UniformBeam {
    /// Span L \[m\].
    pub length: f64,
    /// Bending stiffness EI [N m²].
    pub bending_stiffness: f64,
    /// Mass per unit length ρA [kg/m].
    pub mass_per_length: f64,
}

impl UniformBeam {
    /// Validate L > 0, EI > 0, ρA > 0 (all finite) and their physical ranges
    /// ([`LENGTH_RANGE`], [`BENDING_STIFFNESS_RANGE`], [`MASS_PER_LENGTH_RANGE`]).
    pub fn new(
        length: f64,
        bending_stiffness: f64,
        mass_per_length: f64,
    ) -> Result<Self, BeamError> {
        let length = positive("length", length)?;
        let bending_stiffness = positive("bending_stiffness", bending_stiffness)?;
        let mass_per_length = positive("mass_per_length", mass_per_length)?;
        Ok(Self {
            length: in_range("length", length, LENGTH_RANGE, "m")?,
            bending_stiffness: in_range(
                "bending_stiffness",
                bending_stiffness,
                BENDING_STIFFNESS_RANGE,
                "N m^2",
            )?,
            mass_per_length: in_range(
                "mass_per_length",
                mass_per_length,
                MASS_PER_LENGTH_RANGE,
                "kg/m",
            )?,
        })
    }

    /// ω = (βL)² √(EI / (ρA L⁴)) for a root βL (references.md §D1.6).
    pub fn circular_frequency(&self, beta_l: f64) -> f64 {
        beta_l
            * beta_l
            * (self.bending_stiffness / (self.mass_per_length * self.length.powi(4))).sqrt()
    }
}

/// Coefficients of one analytic mode.
#[derive(Debug, Clone, Copy, PartialEq)]
enum ModeForm {
    /// w = amp sin(k x), k = nπ/L.
    Sine { k: f64, amp: f64 },
    /// Stable form (references.md §D1.6) with ξ = x/L:
    /// φ = a e^(−βξ) + b e^(−β(1−ξ)) + t (−cos βξ + σ sin βξ), w = amp φ.
    Stable {
        beta: f64,
        a: f64,
        b: f64,
        sigma: f64,
        trig_sign: f64,
        amp: f64,
    },
    /// Rigid translation w = amp.
    Translation { amp: f64 },
    /// Rigid rotation about midspan w = amp (x − L/2).
    Rotation { amp: f64 },
}

/// Analytic modes of a uniform single-span beam ([`Support`]), mass-normalised.
#[derive(Debug, Clone, PartialEq)]
pub struct AnalyticBeam {
    support: Support,
    beam: UniformBeam,
    roots: Vec<f64>,
    omegas: Vec<f64>,
    forms: Vec<ModeForm>,
}

impl AnalyticBeam {
    /// Build the first `n_modes` modes (rigid-body modes first for free–free).
    pub fn new(support: Support, beam: UniformBeam, n_modes: usize) -> Result<Self, BeamError> {
        if n_modes == 0 {
            return Err(BeamError::InvalidCount {
                name: "n_modes",
                value: 0,
                reason: "at least one mode is needed",
            });
        }
        // Roots, frequencies and forms: about 64 bytes per mode.
        check_size("n_modes", n_modes, MAX_MODES, "the analytic basis", |n| {
            64.0 * n as f64
        })?;
        let beam = UniformBeam::new(beam.length, beam.bending_stiffness, beam.mass_per_length)?;
        let rho_l = beam.mass_per_length * beam.length;
        let mut roots = Vec::with_capacity(n_modes);
        let mut omegas = Vec::with_capacity(n_modes);
        let mut forms = Vec::with_capacity(n_modes);
        for j in 0..n_modes {
            let (root, form) = match (support, j) {
                (Support::FreeFree, 0) => (
                    0.0,
                    ModeForm::Translation {
                        amp: 1.0 / rho_l.sqrt(),
                    },
                ),
                (Support::FreeFree, 1) => (
                    0.0,
                    ModeForm::Rotation {
                        amp: (12.0 / (rho_l * beam.length * beam.length)).sqrt(),
                    },
                ),
                _ => {
                    let n = j + 1 - support.rigid_modes();
                    let root = characteristic_root(support, n)?;
                    (root, elastic_form(support, root, n, &beam))
                }
            };
            roots.push(root);
            omegas.push(beam.circular_frequency(root));
            forms.push(form);
        }
        Ok(Self {
            support,
            beam,
            roots,
            omegas,
            forms,
        })
    }

    /// Boundary conditions.
    pub fn support(&self) -> Support {
        self.support
    }

    /// Beam properties.
    pub fn beam(&self) -> UniformBeam {
        self.beam
    }

    /// Dimensionless roots β_j L (0 for rigid-body modes).
    pub fn roots(&self) -> &[f64] {
        &self.roots
    }

    fn eval_form(&self, form: &ModeForm, x: f64, d: Derivative) -> f64 {
        let l = self.beam.length;
        match *form {
            ModeForm::Sine { k, amp } => {
                let (s, c) = (k * x).sin_cos();
                match d {
                    Derivative::Shape => amp * s,
                    Derivative::Slope => amp * k * c,
                    Derivative::Curvature => -amp * k * k * s,
                    Derivative::Third => -amp * k * k * k * c,
                }
            }
            ModeForm::Stable {
                beta,
                a,
                b,
                sigma,
                trig_sign,
                amp,
            } => {
                let xi = x / l;
                let e_left = a * (-beta * xi).exp();
                let e_right = b * (-beta * (1.0 - xi)).exp();
                let (s, c) = (beta * xi).sin_cos();
                let k = beta / l;
                let t = trig_sign;
                match d {
                    Derivative::Shape => amp * (e_left + e_right + t * (-c + sigma * s)),
                    Derivative::Slope => amp * k * (-e_left + e_right + t * (s + sigma * c)),
                    Derivative::Curvature => amp * k * k * (e_left + e_right + t * (c - sigma * s)),
                    Derivative::Third => {
                        amp * k * k * k * (-e_left + e_right - t * (s + sigma * c))
                    }
                }
            }
            ModeForm::Translation { amp } => match d {
                Derivative::Shape => amp,
                _ => 0.0,
            },
            ModeForm::Rotation { amp } => match d {
                Derivative::Shape => amp * (x - 0.5 * l),
                Derivative::Slope => amp,
                _ => 0.0,
            },
        }
    }
}

/// Coefficients of the stable form for elastic mode `n` with root β = β_nL (references.md §D1.6):
/// e = e^(−β), s = sin β, c = cos β;
/// CC, CP, FF: den = 1 − 2es − e², σ = (1 − 2ec + e²)/den, tail = (c − s − e)/den;
/// cantilever: den = 1 + 2es − e², σ = (1 + 2ec + e²)/den, tail = (s − c − e)/den;
/// φ = ½(1+σ) e^(−βξ) + tail e^(−β(1−ξ)) ∓ (cos βξ − σ sin βξ) (minus for CC/CP/CF, plus for FF).
/// With these, ∫₀^L φ² dx = L, so w = φ / √(ρA L); SS: w = √(2/(ρA L)) sin(nπx/L).
fn elastic_form(support: Support, beta: f64, n: usize, beam: &UniformBeam) -> ModeForm {
    let rho_l = beam.mass_per_length * beam.length;
    if support == Support::SimplySupported {
        return ModeForm::Sine {
            k: n as f64 * PI / beam.length,
            amp: (2.0 / rho_l).sqrt(),
        };
    }
    let e = (-beta).exp();
    let (s, c) = beta.sin_cos();
    let (sigma, tail) = if support == Support::ClampedFree {
        let den = 1.0 + 2.0 * e * s - e * e;
        ((1.0 + 2.0 * e * c + e * e) / den, (s - c - e) / den)
    } else {
        let den = 1.0 - 2.0 * e * s - e * e;
        ((1.0 - 2.0 * e * c + e * e) / den, (c - s - e) / den)
    };
    let trig_sign = if support == Support::FreeFree {
        -1.0
    } else {
        1.0
    };
    ModeForm::Stable {
        beta,
        a: 0.5 * (1.0 + sigma),
        b: tail,
        sigma,
        trig_sign,
        amp: 1.0 / rho_l.sqrt(),
    }
}

impl ModalBasis for AnalyticBeam {
    fn n_modes(&self) -> usize {
        self.forms.len()
    }

    fn length(&self) -> f64 {
        self.beam.length
    }

    fn circular_frequencies(&self) -> &[f64] {
        &self.omegas
    }

    fn eval_all(&self, x: f64, d: Derivative, out: &mut [f64]) -> Result<(), BeamError> {
        check_len("out", out.len(), self.forms.len())?;
        inside_span("x", x, self.beam.length)?;
        for (o, form) in out.iter_mut().zip(&self.forms) {
            *o = self.eval_form(form, x, d);
        }
        Ok(())
    }

    fn mode_value(&self, j: usize, x: f64, d: Derivative) -> Result<f64, BeamError> {
        check_mode(j, self.forms.len())?;
        inside_span("x", x, self.beam.length)?;
        Ok(self.eval_form(&self.forms[j], x, d))
    }

    fn bending_stiffness(&self, x: f64) -> Result<f64, BeamError> {
        inside_span("x", x, self.beam.length)?;
        Ok(self.beam.bending_stiffness)
    }
}
