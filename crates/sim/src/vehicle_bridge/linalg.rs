//! Linear algebra of the coupled step (references.md §D4.2).
//!
//! The contact-free step matrix `A = c_M M + c_C C + c_K K` of the bridge modes and the vehicle
//! is block diagonal: one 1×1 block per bridge mode (mass-normalised modal equations) and one
//! 1×1 or 2×2 block per wheel (wheel mass, suspension spring–damper, body mass), so `A⁻¹v`
//! costs O(n). The contact adds a low-rank term `U Vᵀ` (one column per wheel in contact):
//!
//! * Sherman–Morrison (one column): `(A + u vᵀ)⁻¹ r = A⁻¹r − A⁻¹u (vᵀA⁻¹r)/(1 + vᵀA⁻¹u)`;
//! * Woodbury (k columns): `(A + U Vᵀ)⁻¹ r = A⁻¹r − A⁻¹U (I_k + VᵀA⁻¹U)⁻¹ VᵀA⁻¹r`, with the
//!   k × k capacitance matrix `I_k + VᵀA⁻¹U` (all wheels couple through the bridge modes).
//!
//! [`contact_update`] applies both in a force form that also admits rigid contacts;
//! [`dense_contact_update`] (Gaussian elimination with partial pivoting on the bordered
//! system) is the reference.

/// A block-diagonal matrix with 1×1 and 2×2 blocks, stored with the block inverses.
#[derive(Debug, Clone, Default)]
pub struct BlockDiagonal {
    n: usize,
    /// (first index, second index or usize::MAX, inverse entries [a, b, c, d] row-major).
    blocks: Vec<(usize, usize, [f64; 4])>,
    /// The matrix entries (same layout), kept for products and dense assembly.
    entries: Vec<[f64; 4]>,
}

/// Marker for a 1×1 block.
const NONE: usize = usize::MAX;

impl BlockDiagonal {
    /// An empty matrix of dimension `n` (every index must then be covered by a block).
    pub fn new(n: usize) -> Self {
        Self {
            n,
            blocks: Vec::with_capacity(n),
            entries: Vec::with_capacity(n),
        }
    }

    /// Removes all blocks (keeps the capacity).
    pub fn clear(&mut self) {
        self.blocks.clear();
        self.entries.clear();
    }

    /// Dimension n.
    pub fn dimension(&self) -> usize {
        self.n
    }

    /// Adds the 1×1 block `a` at index `i`. Returns `false` if `a` is zero or not finite.
    pub fn push1(&mut self, i: usize, a: f64) -> bool {
        if a == 0.0 || !a.is_finite() {
            return false;
        }
        self.blocks.push((i, NONE, [1.0 / a, 0.0, 0.0, 0.0]));
        self.entries.push([a, 0.0, 0.0, 0.0]);
        true
    }

    /// Adds the 2×2 block `[[a, b], [c, d]]` on indices (i, j). Returns `false` if singular.
    pub fn push2(&mut self, i: usize, j: usize, a: f64, b: f64, c: f64, d: f64) -> bool {
        let det = a * d - b * c;
        if det == 0.0 || !det.is_finite() {
            return false;
        }
        self.blocks
            .push((i, j, [d / det, -b / det, -c / det, a / det]));
        self.entries.push([a, b, c, d]);
        true
    }

    /// `x ← A⁻¹ x` in place.
    pub fn solve_in_place(&self, x: &mut [f64]) {
        for &(i, j, inv) in &self.blocks {
            if j == NONE {
                x[i] *= inv[0];
            } else {
                let (xi, xj) = (x[i], x[j]);
                x[i] = inv[0] * xi + inv[1] * xj;
                x[j] = inv[2] * xi + inv[3] * xj;
            }
        }
    }

    /// `x ← |A⁻¹| x` in place, with the entrywise absolute value of each block's inverse (a
    /// bound on how an error vector of x's magnitudes propagates through a solve).
    pub fn solve_abs_in_place(&self, x: &mut [f64]) {
        for &(i, j, inv) in &self.blocks {
            if j == NONE {
                x[i] *= inv[0].abs();
            } else {
                let (xi, xj) = (x[i], x[j]);
                x[i] = inv[0].abs() * xi + inv[1].abs() * xj;
                x[j] = inv[2].abs() * xi + inv[3].abs() * xj;
            }
        }
    }

    /// `y = A x`.
    pub fn mul(&self, x: &[f64], y: &mut [f64]) {
        for (&(i, j, _), e) in self.blocks.iter().zip(&self.entries) {
            if j == NONE {
                y[i] = e[0] * x[i];
            } else {
                y[i] = e[0] * x[i] + e[1] * x[j];
                y[j] = e[2] * x[i] + e[3] * x[j];
            }
        }
    }

    /// The dense matrix, row-major n × n.
    pub fn to_dense(&self) -> Vec<f64> {
        let n = self.n;
        let mut a = vec![0.0; n * n];
        for (&(i, j, _), e) in self.blocks.iter().zip(&self.entries) {
            a[i * n + i] = e[0];
            if j != NONE {
                a[i * n + j] = e[1];
                a[j * n + i] = e[2];
                a[j * n + j] = e[3];
            }
        }
        a
    }
}

/// Solves the dense system `a x = b` (row-major n × n, overwritten) by Gaussian elimination with
/// partial pivoting; `b` is overwritten with x. Returns `false` if a pivot is zero.
pub fn dense_solve(a: &mut [f64], b: &mut [f64]) -> bool {
    let n = b.len();
    debug_assert_eq!(a.len(), n * n);
    for k in 0..n {
        let p = (k..n)
            .max_by(|&i, &j| a[i * n + k].abs().total_cmp(&a[j * n + k].abs()))
            .unwrap_or(k);
        if a[p * n + k] == 0.0 || !a[p * n + k].is_finite() {
            return false;
        }
        if p != k {
            for c in 0..n {
                a.swap(k * n + c, p * n + c);
            }
            b.swap(k, p);
        }
        let piv = a[k * n + k];
        for i in k + 1..n {
            let f = a[i * n + k] / piv;
            if f != 0.0 {
                for c in k..n {
                    a[i * n + c] -= f * a[k * n + c];
                }
                b[i] -= f * b[k];
            }
        }
    }
    for k in (0..n).rev() {
        let s: f64 = (k + 1..n).map(|c| a[k * n + c] * b[c]).sum();
        b[k] = (b[k] - s) / a[k * n + k];
    }
    true
}

/// Work space of [`contact_update`] for up to `k_max` wheels.
#[derive(Debug, Clone, Default)]
pub struct CapacitanceWork {
    ainv_g: Vec<Vec<f64>>,
    cap: Vec<f64>,
}

impl CapacitanceWork {
    /// Work space for dimension n and up to `k_max` wheels.
    pub fn new(n: usize, k_max: usize) -> Self {
        Self {
            ainv_g: vec![vec![0.0; n]; k_max],
            cap: vec![0.0; k_max * k_max],
        }
    }
}

/// One linearised (quasi-)Newton update of the coupled step (references.md §D4.2), in the
/// capacitance form that also covers rigid contacts.
///
/// Unknowns: the state increment Δx and the force increments ΔF_c of the active wheels. The
/// generalized contact force of wheel c is `−F_c ĝ_c` with weight `s = 1 − α_f`, its approach
/// `δ_c = v_cᵀx + r_c`, and the linearised contact law `v_cᵀΔx = compliance_c ΔF_c − δ̃_c`
/// (compliance = 1/k_c; for a rigid contact compliance = 0 and δ̃ = δ, for a compliant one
/// δ̃ = 0). With `A Δx + s Ĝ ΔF = −R`:
///
/// ```text
/// (K_c⁻¹ + s VᵀA⁻¹Ĝ) ΔF = Vᵀ A⁻¹(−R) + δ̃,     Δx = A⁻¹(−R) − s A⁻¹Ĝ ΔF.
/// ```
///
/// For compliant contacts this is the Woodbury formula for `(A + s Ĝ K_c Vᵀ)⁻¹` (capacitance
/// matrix scaled by K_c⁻¹) and, for one wheel, Sherman–Morrison with the denominator
/// `1 + λ`, `λ = s k_c vᵀA⁻¹ĝ` (references.md §D4.2). On entry `x` holds −R; on exit Δx, and `df`
/// holds ΔF. Returns `false` if the capacitance matrix is singular.
pub fn contact_update(
    a: &BlockDiagonal,
    s: f64,
    g_hat: &[impl AsRef<[f64]>],
    v: &[impl AsRef<[f64]>],
    compliance: &[f64],
    delta_tilde: &[f64],
    x: &mut [f64],
    df: &mut [f64],
    work: &mut CapacitanceWork,
) -> bool {
    let k = g_hat.len();
    a.solve_in_place(x);
    if k == 0 {
        return true;
    }
    if work.ainv_g.len() < k || work.ainv_g[0].len() != x.len() {
        *work = CapacitanceWork::new(x.len(), k);
    }
    for c in 0..k {
        work.ainv_g[c].copy_from_slice(g_hat[c].as_ref());
        a.solve_in_place(&mut work.ainv_g[c]);
    }
    if k == 1 {
        // Sherman–Morrison: ΔF = (vᵀy + δ̃)/(1/k_c + s vᵀA⁻¹ĝ) = k_c(vᵀy + δ̃)/(1 + λ).
        let den = compliance[0] + s * dot(v[0].as_ref(), &work.ainv_g[0]);
        if den == 0.0 || !den.is_finite() {
            return false;
        }
        df[0] = (dot(v[0].as_ref(), x) + delta_tilde[0]) / den;
    } else {
        let cap = &mut work.cap[..k * k];
        for r in 0..k {
            for c in 0..k {
                let diag = if r == c { compliance[r] } else { 0.0 };
                cap[r * k + c] = diag + s * dot(v[r].as_ref(), &work.ainv_g[c]);
            }
            df[r] = dot(v[r].as_ref(), x) + delta_tilde[r];
        }
        if !dense_solve(cap, &mut df[..k]) {
            return false;
        }
    }
    for c in 0..k {
        let f = s * df[c];
        for (xi, wi) in x.iter_mut().zip(&work.ainv_g[c]) {
            *xi -= f * wi;
        }
    }
    true
}

/// The same update as [`contact_update`] by one dense solve of the bordered system
///
/// ```text
/// [ A    s Ĝ  ] [Δx]   [ −R ]
/// [ Vᵀ  −K_c⁻¹] [ΔF] = [ −δ̃ ]
/// ```
///
/// (the reference "full Newton" solve). Same argument conventions; `work` is resized as needed.
pub fn dense_contact_update(
    a: &BlockDiagonal,
    s: f64,
    g_hat: &[impl AsRef<[f64]>],
    v: &[impl AsRef<[f64]>],
    compliance: &[f64],
    delta_tilde: &[f64],
    x: &mut [f64],
    df: &mut [f64],
    work: &mut Vec<f64>,
) -> bool {
    let n = x.len();
    let k = g_hat.len();
    let m = n + k;
    work.clear();
    work.resize(m * m + m, 0.0);
    let (mat, rhs) = work.split_at_mut(m * m);
    let dense_a = a.to_dense();
    for i in 0..n {
        mat[i * m..i * m + n].copy_from_slice(&dense_a[i * n..(i + 1) * n]);
        for c in 0..k {
            mat[i * m + n + c] = s * g_hat[c].as_ref()[i];
        }
        rhs[i] = x[i];
    }
    for c in 0..k {
        mat[(n + c) * m..(n + c) * m + n].copy_from_slice(v[c].as_ref());
        mat[(n + c) * m + n + c] = -compliance[c];
        rhs[n + c] = -delta_tilde[c];
    }
    if !dense_solve(mat, rhs) {
        return false;
    }
    x.copy_from_slice(&rhs[..n]);
    df[..k].copy_from_slice(&rhs[n..]);
    true
}

/// The dot product.
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}
