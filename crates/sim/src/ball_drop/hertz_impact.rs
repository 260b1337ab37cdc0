//! The Hertz impact closed form (references.md §D1.4).

/// Hertz impact closed form (references.md §D1.4, references.md §C4.10; Johnson 1985 §11.4).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct HertzImpact {
    /// Impact speed v \[m/s\].
    pub impact_speed: f64,
    /// Maximum approach δ* \[m\] from the energy balance
    /// `(2/5) K δ*^{5/2} = ½ m v² + m g δ*` (g = 0: `δ* = (15 m v²/(16 E*√R))^{2/5}`).
    pub max_approach: f64,
    /// Peak force `F* = K δ*^{3/2}` \[N\].
    pub peak_force: f64,
    /// Contact duration without gravity, `t_c = (4/5) B(2/5, ½) δ₀*/v = 2.9432752 δ₀*/v`
    /// with the gravity-free δ₀* \[s\]. (From `t_c = 2 ∫₀^{δ*} dδ / √(v² − (4K/5m) δ^{5/2})`;
    /// gravity lengthens it by a relative O(m g/F*).)
    pub contact_duration: f64,
}

/// `(4/5) B(2/5, 1/2)`: the Hertz contact-time constant (references.md §D1.4 gives 2.9432).
pub const CONTACT_TIME_FACTOR: f64 = 2.943_275_184_324_705;

impl HertzImpact {
    /// The impact of mass `m` \[kg\] at speed `v` \[m/s\] on `F = K δ^{3/2}` under gravity `g`.
    pub fn new(m: f64, k: f64, v: f64, g: f64) -> Self {
        let free = (1.25 * m * v * v / k).powf(0.4);
        // f(δ) = (2/5)Kδ^{5/2} − m g δ − ½ m v² is convex for δ > 0 with f(0) ≤ 0: one
        // positive root, bracketed and found by bisection to round-off.
        let f = |d: f64| 0.4 * k * d * d * d.sqrt() - m * g * d - 0.5 * m * v * v;
        let mut hi = free.max((2.5 * m * g / k).powf(2.0 / 3.0)).max(1e-300) * 2.0;
        while f(hi) <= 0.0 && hi.is_finite() {
            hi *= 2.0;
        }
        let mut lo = 0.0;
        for _ in 0..2000 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if f(mid) > 0.0 {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        let delta = if v == 0.0 && g == 0.0 { 0.0 } else { hi };
        Self {
            impact_speed: v,
            max_approach: delta,
            peak_force: k * delta.powf(1.5),
            contact_duration: if v > 0.0 {
                CONTACT_TIME_FACTOR * free / v
            } else {
                f64::INFINITY
            },
        }
    }
}
