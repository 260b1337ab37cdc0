//! The Radau IIA(5) coefficients of RADAU5 (Hairer & Wanner, Solving ODEs II, §IV.8; the
//! constants quoted with RADAU5's 20 digits).

#![allow(clippy::excessive_precision)]

pub(super) const SQ6: f64 = 2.449_489_742_783_178;
pub(super) const C1: f64 = (4.0 - SQ6) / 10.0;
pub(super) const C2: f64 = (4.0 + SQ6) / 10.0;
pub(super) const C1M1: f64 = C1 - 1.0;
pub(super) const C2M1: f64 = C2 - 1.0;
pub(super) const C1MC2: f64 = C1 - C2;
/// Error-estimate weights `e = γ̂ ⋅ b̂ − …` of RADAU5 (`DD1..DD3`), divided by h in use.
pub(super) const DD1: f64 = -(13.0 + 7.0 * SQ6) / 3.0;
pub(super) const DD2: f64 = (-13.0 + 7.0 * SQ6) / 3.0;
pub(super) const DD3: f64 = -1.0 / 3.0;
/// Transformation `T` and its inverse (RADAU5; `T₃₂ = 1`, `T₃₃ = 0`).
pub(super) const T11: f64 = 9.123_239_487_089_294_279e-2;
pub(super) const T12: f64 = -0.141_255_295_020_954_208_43;
pub(super) const T13: f64 = -3.002_919_410_514_742_449_2e-2;
pub(super) const T21: f64 = 0.241_717_932_707_107_018_96;
pub(super) const T22: f64 = 0.204_129_352_293_799_931_99;
pub(super) const T23: f64 = 0.382_942_112_757_261_937_79;
pub(super) const T31: f64 = 0.966_048_182_615_092_936_19;
pub(super) const TI11: f64 = 4.325_579_890_063_155_351;
pub(super) const TI12: f64 = 0.339_199_251_815_809_869_54;
pub(super) const TI13: f64 = 0.541_770_539_935_874_871_19;
pub(super) const TI21: f64 = -4.178_718_591_551_904_727_3;
pub(super) const TI22: f64 = -0.327_682_820_761_062_387_08;
pub(super) const TI23: f64 = 0.476_623_554_500_550_451_96;
pub(super) const TI31: f64 = -0.502_872_634_945_786_875_95;
pub(super) const TI32: f64 = 2.571_926_949_855_605_429_2;
pub(super) const TI33: f64 = -0.596_039_204_828_224_924_97;

/// Eigenvalues of `A⁻¹`: real `γ̂ = 1/u₁` and complex pair `α̂ ± iβ̂`.
pub(super) fn eigenvalues_of_a_inverse() -> (f64, f64, f64) {
    let cbrt81 = 81f64.cbrt();
    let cbrt9 = 9f64.cbrt();
    let u1 = (6.0 + cbrt81 - cbrt9) / 30.0;
    let alph = (12.0 - cbrt81 + cbrt9) / 60.0;
    let beta = (cbrt81 + cbrt9) * 3f64.sqrt() / 60.0;
    let cno = alph * alph + beta * beta;
    (1.0 / u1, alph / cno, beta / cno)
}
