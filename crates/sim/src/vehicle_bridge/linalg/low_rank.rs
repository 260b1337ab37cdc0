//! The low-rank contact update of the coupled step (module [`super`]): Sherman–Morrison /
//! Woodbury in capacitance form, factorised per group of coupled wheels, and the dense
//! bordered solve that is its reference.

use integrate::DenseLu;

use super::banded::BandedLu;
use super::{BlockDiagonal, Singular};

mod entries;
mod folding;
mod groups;

/// Work space of [`contact_update`]: A⁻¹ĝ per wheel with its support and blocks, the
/// coupling groups, and the LU storage of each capacitance size met (allocated at its first
/// use, then reused).
///
/// **Reuse.** A⁻¹ĝ of a wheel is kept with the ĝ (on its pattern) and the version of A it
/// was computed from, and recomputed only when one of them changed. Within a time step ĝ
/// changes only with the column forces (a point contact's ĝ is the mode shapes at the wheel,
/// fixed by its position), and for a wheel off the span it is the unit vector of the wheel's
/// DOF in every step, so most solves are reused. The reuse is exact: a reused vector is the
/// one the solve would give (same inputs, same operations).
#[derive(Debug, Default)]
pub struct CapacitanceWork {
    /// Per wheel: A⁻¹ĝ (n; zero outside `support`).
    ainv_g: Vec<Vec<f64>>,
    /// Per wheel: where A⁻¹ĝ can be non-zero.
    support: Vec<Vec<usize>>,
    /// Per wheel: the blocks of A that A⁻¹ĝ touches.
    blocks: Vec<Vec<usize>>,
    /// Per wheel: the key of the stored A⁻¹ĝ (A's version, the pattern and ĝ on it).
    key: Vec<SolveKey>,
    /// Per wheel: the identity of its A⁻¹ĝ (the solve count at its last fresh solve), and
    /// the capacitance entries kept with such identities (module `entries`).
    g_id: Vec<u64>,
    entries: entries::EntryCache,
    /// Per block of A: the stamp of the last solve that applied it.
    mark: Vec<u64>,
    /// Per block of A: (stamp, first wheel of this update that touched it).
    first: Vec<(u64, usize)>,
    stamp: u64,
    /// Union–find parents of the active wheels (coupling groups).
    parent: Vec<usize>,
    /// The active wheels ordered by group, and the start of each group in it.
    order: Vec<usize>,
    group_start: Vec<usize>,
    /// What `order` and `group_start` were formed from (kept while it is the same).
    groups_key: groups::GroupsKey,
    rhs: Vec<f64>,
    /// The capacitance matrix of one group (row-major).
    cap: Vec<f64>,
    lu: Vec<DenseLu<f64>>,
    /// Solves done and reused (statistics for benchmarks and tests).
    solves: u64,
    reused: u64,
    /// Per position in `active`: the wheel is folded into its block's band ([`contact_update`],
    /// "Folding").
    folded: Vec<bool>,
    /// Per position in `active`, of a folded wheel: its block and its index in the block's
    /// `fold_add` (and `fold_key`).
    fold_slot: Vec<(usize, usize)>,
    /// Per dense block of A: the diagonal additions of its folded wheels (block position,
    /// value), whether it has any, and the factorisation of the block with them.
    fold_add: Vec<Vec<(usize, f64)>>,
    fold_used: Vec<bool>,
    fold_lu: Vec<BandedLu>,
    /// Folded wheels so far (statistics).
    folds: u64,
    /// Updates whose coupling groups were kept from the last one (statistics).
    groups_kept: u64,
    /// Per dense block: what `fold_lu` was factorised from (A's version, 0 for nothing
    /// valid, and the diagonal additions bit for bit), and the factorisations so reused.
    fold_key: Vec<(u64, Vec<(usize, u64)>)>,
    fold_reused: u64,
    /// The wheels solved with the folded blocks in this update, the right-hand sides of one
    /// block (a wheel, or `usize::MAX` for the step's), and their interleaved band-order
    /// scratch ([`BandedLu::solve_interleaved`]).
    batch: Vec<usize>,
    rows: Vec<usize>,
    many_buf: Vec<f64>,
    /// Per dense block: the generation of `fold_lu` (unique, 0 for none valid).
    fold_gen: Vec<u64>,
    /// The source of generations.
    fold_gens: u64,
    /// Relative change of a folded wheel's diagonal addition within which the factorisation
    /// of the folded block is kept ([`Self::set_fold_tolerance`]; 0: reused only bit for bit).
    fold_tolerance: f64,
    /// Per wheel: its A_c⁻¹ĝ on a folded block, kept with what it was computed from
    /// (`folding::FoldColumn`).
    fold_column: Vec<folding::FoldColumn>,
    /// Wheel columns on folded blocks reused (statistics).
    column_reused: u64,
}

/// What a stored A⁻¹ĝ was computed from.
#[derive(Debug, Default, Clone)]
struct SolveKey {
    /// The version of A (0: nothing stored).
    version: u64,
    pattern: Vec<usize>,
    /// ĝ on the pattern, bit for bit.
    g: Vec<u64>,
}

impl SolveKey {
    #[inline(always)]
    fn matches(&self, version: u64, g: &[f64], pattern: &[usize]) -> bool {
        if self.version != version || self.pattern.len() != pattern.len() {
            return false;
        }
        // A wheel on the span: the modes 0..m, then its own DOF (as in `pattern_dot`; both
        // patterns ascending, so each is determined by its length and last index). Every bit
        // of ĝ equal: the OR of the XORs over the contiguous modes is zero.
        if let (Some(m), &[0, .., m_minus_1, last]) = (contiguous_modes(&self.pattern), pattern)
            && m_minus_1 + 2 == pattern.len()
            && self.pattern[m] == last
        {
            let modes = g[..m]
                .iter()
                .zip(&self.g[..m])
                .fold(0, |d, (x, &bits)| d | (x.to_bits() ^ bits));
            return modes | (g[last].to_bits() ^ self.g[m]) == 0;
        }
        // One pass over the pattern (indices and ĝ's bits together).
        pattern
            .iter()
            .zip(&self.pattern)
            .zip(&self.g)
            .all(|((&i, &stored), &bits)| i == stored && g[i].to_bits() == bits)
    }

    fn set(&mut self, version: u64, g: &[f64], pattern: &[usize]) {
        self.version = version;
        self.pattern.clear();
        self.pattern.extend_from_slice(pattern);
        self.g.clear();
        self.g.extend(pattern.iter().map(|&i| g[i].to_bits()));
    }
}

impl CapacitanceWork {
    /// Work space for dimension n and up to `k_max` wheels.
    pub fn new(n: usize, k_max: usize) -> Self {
        let mut work = Self::default();
        work.reserve(n, k_max, 0);
        work
    }

    /// Makes room for `k` wheels of dimension `n` and `blocks` blocks of A (allocates only
    /// when they grow).
    fn reserve(&mut self, n: usize, k: usize, blocks: usize) {
        if self.ainv_g.first().is_some_and(|a| a.len() != n) {
            self.ainv_g.clear();
            self.support.clear();
            self.blocks.clear();
            self.key.clear();
            self.g_id.clear();
            self.fold_column.clear();
            self.groups_key.valid = false;
        }
        while self.ainv_g.len() < k {
            self.fold_column.push(folding::FoldColumn::default());
            self.ainv_g.push(vec![0.0; n]);
            self.support.push(Vec::new());
            self.blocks.push(Vec::new());
            self.key.push(SolveKey::default());
            self.g_id.push(0);
        }
        if self.mark.len() != blocks {
            self.mark = vec![0; blocks];
            self.first = vec![(0, 0); blocks];
            self.stamp = 0;
            self.groups_key.valid = false;
        }
    }

    /// A⁻¹ĝ of `wheel` into `ainv_g[wheel]`, reused when its key matches.
    fn solve_wheel(&mut self, a: &BlockDiagonal, wheel: usize, g: &[f64], pattern: &[usize]) {
        if self.key[wheel].matches(a.version(), g, pattern) {
            self.reused += 1;
            return;
        }
        self.solve_wheel_fresh(a, wheel, g, pattern);
        self.key[wheel].set(a.version(), g, pattern);
    }

    /// A⁻¹ĝ of `wheel` into `ainv_g[wheel]`, its support and blocks.
    fn solve_wheel_fresh(&mut self, a: &BlockDiagonal, wheel: usize, g: &[f64], pattern: &[usize]) {
        self.start_wheel(wheel, g, pattern);
        a.solve_pattern_in_place(
            &mut self.ainv_g[wheel],
            pattern,
            &mut self.support[wheel],
            &mut self.blocks[wheel],
            &mut self.mark,
            self.stamp,
        );
    }

    /// Sets `ainv_g[wheel]` to ĝ (zero off `pattern`) for a pattern solve with the next
    /// stamp (counted as a solve).
    fn start_wheel(&mut self, wheel: usize, g: &[f64], pattern: &[usize]) {
        self.solves += 1;
        self.g_id[wheel] = self.solves;
        let x = &mut self.ainv_g[wheel];
        for &i in &self.support[wheel] {
            x[i] = 0.0;
        }
        for &i in pattern {
            x[i] = g[i];
        }
        self.stamp += 1;
    }

    /// The wheels folded into a band so far ([`contact_update`], "Folding").
    pub fn fold_count(&self) -> u64 {
        self.folds
    }

    /// `vᵀA⁻¹g` of `wheel` for vectors zero outside `pattern` (over the blocks g touches; no
    /// full solve; A⁻¹g is kept for [`contact_update`]).
    pub fn quadratic_form(
        &mut self,
        a: &BlockDiagonal,
        wheel: usize,
        g: &[f64],
        v: &[f64],
        pattern: &[usize],
    ) -> f64 {
        self.reserve(g.len(), wheel + 1, a.block_count());
        self.solve_wheel(a, wheel, g, pattern);
        pattern.iter().map(|&i| v[i] * self.ainv_g[wheel][i]).sum()
    }

    /// The pattern solves done and reused so far: (A⁻¹ĝ computed, A⁻¹ĝ reused).
    pub fn solve_counts(&self) -> (u64, u64) {
        (self.solves, self.reused)
    }

    /// Updates whose coupling groups were kept from the update before (statistics).
    pub fn groups_kept(&self) -> u64 {
        self.groups_kept
    }

    /// The next stamp (never 0, the initial mark).
    fn next_stamp(&mut self) -> u64 {
        self.stamp += 1;
        self.stamp
    }
}

/// Work space of [`dense_contact_update`]: the LU of each bordered size n + k met so far
/// (allocated at the first use of a size) and the right-hand side.
#[derive(Debug, Default)]
pub struct DenseWork {
    lu: Vec<DenseLu<f64>>,
    rhs: Vec<f64>,
}

/// The LU storage for an `m × m` matrix among `lus` (added at the first use of a size).
fn lu_of_size(lus: &mut Vec<DenseLu<f64>>, m: usize) -> &mut DenseLu<f64> {
    let i = match lus.iter().position(|lu| lu.dim() == m) {
        Some(i) => i,
        None => {
            lus.push(DenseLu::new(m));
            lus.len() - 1
        }
    };
    &mut lus[i]
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
/// `1 + λ`, `λ = s k_c vᵀA⁻¹ĝ` (references.md §D4.2).
///
/// **Sparsity.** Wheel c's vectors ĝ_c and v_c are zero outside `pattern[c]` (the bridge modes
/// and the wheel's own DOF), so A⁻¹ĝ_c is non-zero only on the blocks of A that ĝ_c touches.
/// Two wheels are coupled (a non-zero capacitance entry) only if they touch a common block:
/// wheels on the span share the modes, wheels of one vehicle share its block. The capacitance
/// matrix is therefore block diagonal over the groups of coupled wheels (union–find over the
/// blocks), and each group is factorised on its own: a long train whose cars are mostly off the
/// span costs O(wheels), not O(wheels³).
///
/// **Folding.** A compliant wheel off the span has ĝ_c = g e_i and v_c = v e_i on its own DOF
/// i only, so its term s ĝ_c v_cᵀ/compliance_c is one diagonal entry of A. When i belongs to a
/// dense block with a band factorisation (an articulated rake, module `banded`), such wheels
/// are folded into that block: A_c = A + Σ_folded s g v/compliance_c e_i e_iᵀ is factorised
/// again in its band (O(m p²)), the right-hand side gets −s g δ̃_c/compliance_c at i, the
/// remaining wheels (on the span, rigid, or of other blocks) take the capacitance form above
/// with A_c in place of A, and each folded wheel's ΔF_c = (v Δx_i + δ̃_c)/compliance_c. The
/// rake's capacitance group then holds its wheels on the span only, instead of all of them
/// (42 for HSLM-A1, a dense 42 × 42 factorisation at every update). The same linear system,
/// solved differently: equal to round-off (tested against the dense bordered solve). With a
/// fold tolerance (`CapacitanceWork::set_fold_tolerance`, used by the quasi-Newton
/// iteration) a factorisation from folded stiffnesses within that relative change is kept:
/// the update is then a chord step for the folded wheels (the iteration converges to the
/// same solution; `tests/vehicle_bridge_banded.rs`).
///
/// Arguments: `pattern[c]` lists the indices where wheel c's vectors can be non-zero, in
/// ascending order; `active` lists the wheels taking part (indices into `g_hat`, `v`, `pattern`);
/// `compliance`, `delta_tilde` and `df` are indexed by position in `active`. On entry `x` holds
/// −R; on exit Δx, and `df` holds ΔF. An error if a capacitance matrix is singular.
#[allow(clippy::too_many_arguments)]
pub fn contact_update(
    a: &BlockDiagonal,
    s: f64,
    g_hat: &[impl AsRef<[f64]>],
    v: &[impl AsRef<[f64]>],
    pattern: &[impl AsRef<[usize]>],
    active: &[usize],
    compliance: &[f64],
    delta_tilde: &[f64],
    x: &mut [f64],
    df: &mut [f64],
    work: &mut CapacitanceWork,
) -> Result<(), Singular> {
    let k = active.len();
    if k == 0 {
        a.solve_in_place(x);
        return Ok(());
    }
    work.reserve(x.len(), g_hat.len(), a.block_count());
    let folding = work.fold_off_span(a, s, g_hat, v, pattern, active, compliance);
    if folding {
        // The folded wheels' −s ĝ δ̃ / compliance on the right-hand side.
        for (c, &wheel) in active.iter().enumerate() {
            if work.folded[c] && delta_tilde[c] != 0.0 {
                let i = pattern[wheel].as_ref()[0];
                x[i] -= s * g_hat[wheel].as_ref()[i] * delta_tilde[c] / compliance[c];
            }
        }
        // The folded blocks are solved below, with the wheels that touch them.
        let used = &work.fold_used;
        a.solve_in_place_deferring(x, |d| used[d]);
    } else {
        a.solve_in_place(x);
    }
    let folded = |work: &CapacitanceWork, c: usize| folding && work.folded[c];
    // A⁻¹ĝ_c (A_c⁻¹ĝ_c) on the blocks ĝ_c touches (the rest of ainv_g[wheel] is kept zero);
    // the wheels touching a folded block all at once, with x's entries on the folded blocks.
    work.batch.clear();
    for (c, &wheel) in active.iter().enumerate() {
        if folded(work, c) {
            continue;
        }
        let (g, p) = (g_hat[wheel].as_ref(), pattern[wheel].as_ref());
        if folding && work.touches_fold(a, p) {
            work.batch.push(wheel);
        } else {
            work.solve_wheel(a, wheel, g, p);
        }
    }
    if folding {
        work.solve_wheels_folded(a, g_hat, pattern, x);
    }
    // Coupling groups: wheels touching a common block (kept from the last update when formed
    // from the same wheels and blocks, `GroupsKey`; always formed when wheels are folded).
    if !folding && work.groups_key.matches(a.version(), active, &work.g_id) {
        work.groups_kept += 1;
    } else {
        work.form_groups(active, folding);
        if folding {
            work.groups_key.valid = false;
        } else {
            work.groups_key.set(a.version(), active, &work.g_id);
        }
    }
    // vᵀx over the pattern (v is zero elsewhere).
    let v_dot =
        |c: usize, y: &[f64]| pattern_dot(pattern[active[c]].as_ref(), v[active[c]].as_ref(), y);
    for g in 0..work.group_start.len() - 1 {
        let members = &work.order[work.group_start[g]..work.group_start[g + 1]];
        let kg = members.len();
        if kg == 1 {
            // Sherman–Morrison: ΔF = (vᵀy + δ̃)/(1/k_c + s vᵀA⁻¹ĝ) = k_c(vᵀy + δ̃)/(1 + λ).
            let c = members[0];
            let den = compliance[c] + s * v_dot(c, &work.ainv_g[active[c]]);
            if den == 0.0 || !den.is_finite() {
                return Err(SINGULAR_CAPACITANCE);
            }
            df[c] = (v_dot(c, x) + delta_tilde[c]) / den;
            continue;
        }
        // Capacitance matrix of the group (its entries s vᵀA⁻¹ĝ kept while their inputs are
        // the same, module `entries`) and its right-hand side.
        let range = work.group_start[g]..work.group_start[g + 1];
        work.group_entries(g, range.clone(), active, s, v, pattern);
        let entries = work.entries.of_group(g);
        let members = &work.order[range];
        work.cap.clear();
        for (r, &cr) in members.iter().enumerate() {
            for (q, &cq) in members.iter().enumerate() {
                let diag = if cr == cq { compliance[cr] } else { 0.0 };
                work.cap.push(diag + entries[r * kg + q]);
            }
        }
        work.rhs.clear();
        for &cr in members {
            work.rhs.push(v_dot(cr, x) + delta_tilde[cr]);
        }
        let solved = if kg <= SMALL_GROUP {
            small_solve_in_place(&mut work.cap, &mut work.rhs)
        } else {
            let lu = lu_of_size(&mut work.lu, kg);
            let mut m = lu.matrix_mut();
            for r in 0..kg {
                for q in 0..kg {
                    m[(r, q)] = work.cap[r * kg + q];
                }
            }
            let factored = lu.factor();
            if factored {
                lu.solve_in_place(&mut work.rhs);
            }
            factored
        };
        if !solved {
            return Err(SINGULAR_CAPACITANCE);
        }
        for (r, &cr) in members.iter().enumerate() {
            df[cr] = work.rhs[r];
        }
    }
    for c in 0..k {
        if folded(work, c) {
            continue;
        }
        let f = s * df[c];
        let wheel = active[c];
        let ainv_g = &work.ainv_g[wheel];
        for &i in &work.support[wheel] {
            x[i] -= f * ainv_g[i];
        }
    }
    // The folded wheels' force increments from the final Δx.
    for (c, &wheel) in active.iter().enumerate() {
        if folded(work, c) {
            let i = pattern[wheel].as_ref()[0];
            df[c] = (v[wheel].as_ref()[i] * x[i] + delta_tilde[c]) / compliance[c];
        }
    }
    Ok(())
}

/// The number of modes m if the ascending `pattern` is the modes `0..m` followed by one more
/// index (a wheel on the span), else `None`.
#[inline(always)]
fn contiguous_modes(pattern: &[usize]) -> Option<usize> {
    match pattern {
        &[0, .., m_minus_1, _] if m_minus_1 + 2 == pattern.len() => Some(pattern.len() - 1),
        _ => None,
    }
}

/// `vᵀy` for a `v` zero outside `pattern` (ascending indices), summed in pattern order.
fn pattern_dot(pattern: &[usize], v: &[f64], y: &[f64]) -> f64 {
    match pattern {
        // A wheel off the span: one term (the same value as the sum).
        &[i] => v[i] * y[i],
        // A wheel on the span: the modes 0..m, then its own DOF. The modes are summed over
        // contiguous slices (no index loads), then the last term: the same products added in
        // the same order as the general sum.
        &[0, .., m_minus_1, last] if m_minus_1 + 2 == pattern.len() => {
            let m = pattern.len() - 1;
            let modes: f64 = v[..m].iter().zip(&y[..m]).map(|(a, b)| a * b).sum();
            modes + v[last] * y[last]
        }
        p => p.iter().map(|&i| v[i] * y[i]).sum(),
    }
}

/// Groups up to this size are solved by [`small_solve_in_place`]; larger ones by
/// `integrate::DenseLu` (blocked kernels, whose set-up costs more than a small elimination).
const SMALL_GROUP: usize = 16;

/// Solves the row-major `m × m` system `a y = b` in place (`b ← y`, `a` destroyed) by Gaussian
/// elimination with partial pivoting (Golub & Van Loan, Algorithm 3.4.1; references.md §R4.1).
/// False if a pivot is zero or not finite (the matrix is singular to working precision).
pub fn small_solve_in_place(a: &mut [f64], b: &mut [f64]) -> bool {
    // The sizes of one vehicle's wheels and of a few vehicles on the span with a fixed
    // size (the compiler unrolls the loops; the same operations in the same order).
    match b.len() {
        2 => fixed_solve_in_place::<2>(a, b),
        3 => fixed_solve_in_place::<3>(a, b),
        4 => fixed_solve_in_place::<4>(a, b),
        8 => fixed_solve_in_place::<8>(a, b),
        _ => any_solve_in_place(a, b),
    }
}

/// [`small_solve_in_place`] for `M` unknowns (row-major `M × M` in `a`).
fn fixed_solve_in_place<const M: usize>(a: &mut [f64], b: &mut [f64]) -> bool {
    if a.len() != M * M || b.len() != M {
        return any_solve_in_place(a, b);
    }
    let a = a.as_chunks_mut::<M>().0;
    let Ok(b) = <&mut [f64; M]>::try_from(b) else {
        return false;
    };
    for col in 0..M {
        let mut pivot = col;
        for r in col + 1..M {
            if a[r][col].abs() > a[pivot][col].abs() {
                pivot = r;
            }
        }
        let p = a[pivot][col];
        if p == 0.0 || !p.is_finite() {
            return false;
        }
        if pivot != col {
            for j in col..M {
                let t = a[pivot][j];
                a[pivot][j] = a[col][j];
                a[col][j] = t;
            }
            b.swap(pivot, col);
        }
        let b_col = b[col];
        for r in col + 1..M {
            let f = a[r][col] / p;
            if f != 0.0 {
                for j in col + 1..M {
                    a[r][j] -= f * a[col][j];
                }
                b[r] -= f * b_col;
            }
        }
    }
    for r in (0..M).rev() {
        let mut y = b[r];
        for j in r + 1..M {
            y -= a[r][j] * b[j];
        }
        b[r] = y / a[r][r];
    }
    true
}

/// [`small_solve_in_place`] for any size.
fn any_solve_in_place(a: &mut [f64], b: &mut [f64]) -> bool {
    let m = b.len();
    for col in 0..m {
        let mut pivot = col;
        for r in col + 1..m {
            if a[r * m + col].abs() > a[pivot * m + col].abs() {
                pivot = r;
            }
        }
        let p = a[pivot * m + col];
        if p == 0.0 || !p.is_finite() {
            return false;
        }
        if pivot != col {
            for j in col..m {
                a.swap(pivot * m + j, col * m + j);
            }
            b.swap(pivot, col);
        }
        // Rows below the pivot row, each updated from the pivot row's slice.
        let (upper, lower) = a.split_at_mut((col + 1) * m);
        let pivot_row = &upper[col * m + col + 1..(col + 1) * m];
        let b_col = b[col];
        for (row, b_r) in lower.chunks_exact_mut(m).zip(&mut b[col + 1..]) {
            let f = row[col] / p;
            if f != 0.0 {
                for (x, &u) in row[col + 1..].iter_mut().zip(pivot_row) {
                    *x -= f * u;
                }
                *b_r -= f * b_col;
            }
        }
    }
    for r in (0..m).rev() {
        let row = &a[r * m..(r + 1) * m];
        let mut y = b[r];
        for (&arj, &bj) in row[r + 1..].iter().zip(&b[r + 1..]) {
            y -= arj * bj;
        }
        b[r] = y / row[r];
    }
    true
}

const SINGULAR_CAPACITANCE: Singular = Singular {
    what: "capacitance matrix",
};

/// The same update as [`contact_update`] by one dense solve of the bordered system
///
/// ```text
/// [ A    s Ĝ  ] [Δx]   [ −R ]
/// [ Vᵀ  −K_c⁻¹] [ΔF] = [ −δ̃ ]
/// ```
///
/// (the reference "full Newton" solve). Same argument conventions; `work` keeps the LU
/// storage of each size met.
#[allow(clippy::too_many_arguments)]
pub fn dense_contact_update(
    a: &BlockDiagonal,
    s: f64,
    g_hat: &[impl AsRef<[f64]>],
    v: &[impl AsRef<[f64]>],
    active: &[usize],
    compliance: &[f64],
    delta_tilde: &[f64],
    x: &mut [f64],
    df: &mut [f64],
    work: &mut DenseWork,
) -> Result<(), Singular> {
    let n = x.len();
    let k = active.len();
    let m = n + k;
    let rhs = &mut work.rhs;
    rhs.clear();
    rhs.resize(m, 0.0);
    let lu = lu_of_size(&mut work.lu, m);
    let mut mat = lu.matrix_mut();
    mat.fill(0.0);
    a.write_into(&mut mat);
    for i in 0..n {
        for (c, &wheel) in active.iter().enumerate() {
            mat[(i, n + c)] = s * g_hat[wheel].as_ref()[i];
        }
        rhs[i] = x[i];
    }
    for (c, &wheel) in active.iter().enumerate() {
        for (j, &vj) in v[wheel].as_ref().iter().enumerate() {
            mat[(n + c, j)] = vj;
        }
        mat[(n + c, n + c)] = -compliance[c];
        rhs[n + c] = -delta_tilde[c];
    }
    if !lu.factor() {
        return Err(Singular {
            what: "bordered matrix",
        });
    }
    lu.solve_in_place(rhs);
    x.copy_from_slice(&rhs[..n]);
    df[..k].copy_from_slice(&rhs[n..]);
    Ok(())
}
