//! The low-rank contact update of the coupled step (module [`super`]): Sherman–Morrison /
//! Woodbury in capacitance form, factorised per group of coupled wheels, and the dense
//! bordered solve that is its reference.

use integrate::DenseLu;

use super::{BlockDiagonal, Singular};

/// Work space of [`contact_update`]: A⁻¹ĝ per wheel with its support and blocks, the
/// coupling groups, and the LU storage of each capacitance size met (allocated at its first
/// use, then reused).
#[derive(Debug, Default)]
pub struct CapacitanceWork {
    ainv_g: Vec<Vec<f64>>,
    /// Where each A⁻¹ĝ can be non-zero (all other entries of `ainv_g[c]` are zero).
    support: Vec<Vec<usize>>,
    /// The blocks of A each A⁻¹ĝ touches.
    blocks: Vec<Vec<usize>>,
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
    rhs: Vec<f64>,
    lu: Vec<DenseLu<f64>>,
    /// Scratch of [`Self::quadratic_form`] (kept zero between calls).
    scratch: Vec<f64>,
    scratch_support: Vec<usize>,
    scratch_blocks: Vec<usize>,
}

impl CapacitanceWork {
    /// Work space for dimension n and up to `k_max` wheels.
    pub fn new(n: usize, k_max: usize) -> Self {
        Self {
            ainv_g: vec![vec![0.0; n]; k_max],
            support: vec![Vec::new(); k_max],
            blocks: vec![Vec::new(); k_max],
            ..Self::default()
        }
    }

    /// Makes room for `k` wheels of dimension `n` and `blocks` blocks of A (allocates only
    /// when they grow).
    fn reserve(&mut self, n: usize, k: usize, blocks: usize) {
        if self.ainv_g.first().is_some_and(|a| a.len() != n) {
            self.ainv_g.clear();
            self.support.clear();
            self.blocks.clear();
        }
        while self.ainv_g.len() < k {
            self.ainv_g.push(vec![0.0; n]);
            self.support.push(Vec::new());
            self.blocks.push(Vec::new());
        }
        if self.mark.len() != blocks {
            self.mark = vec![0; blocks];
            self.first = vec![(0, 0); blocks];
            self.stamp = 0;
        }
    }

    /// `vᵀA⁻¹g` for vectors zero outside `pattern` (over the blocks g touches; no full solve).
    pub fn quadratic_form(
        &mut self,
        a: &BlockDiagonal,
        g: &[f64],
        v: &[f64],
        pattern: &[usize],
    ) -> f64 {
        let n = g.len();
        if self.scratch.len() != n {
            self.scratch = vec![0.0; n];
        }
        self.reserve(n, 0, a.block_count());
        for &i in pattern {
            self.scratch[i] = g[i];
        }
        let stamp = self.next_stamp();
        a.solve_pattern_in_place(
            &mut self.scratch,
            pattern,
            &mut self.scratch_support,
            &mut self.scratch_blocks,
            &mut self.mark,
            stamp,
        );
        let result = pattern.iter().map(|&i| v[i] * self.scratch[i]).sum();
        for &i in self.scratch_support.iter().chain(pattern) {
            self.scratch[i] = 0.0;
        }
        result
    }

    /// The next stamp (never 0, the initial mark).
    fn next_stamp(&mut self) -> u64 {
        self.stamp += 1;
        self.stamp
    }
}

fn find(parent: &mut [usize], mut a: usize) -> usize {
    while parent[a] != a {
        parent[a] = parent[parent[a]];
        a = parent[a];
    }
    a
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
/// Arguments: `active` lists the wheels taking part (indices into `g_hat`, `v`, `pattern`);
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
    a.solve_in_place(x);
    if k == 0 {
        return Ok(());
    }
    let n = x.len();
    work.reserve(n, k, a.block_count());
    // A⁻¹ĝ_c on the blocks ĝ_c touches (the rest of ainv_g[c] is kept zero).
    for (c, &wheel) in active.iter().enumerate() {
        for &i in &work.support[c] {
            work.ainv_g[c][i] = 0.0;
        }
        let g = g_hat[wheel].as_ref();
        let p = pattern[wheel].as_ref();
        for &i in p {
            work.ainv_g[c][i] = g[i];
        }
        let stamp = work.next_stamp();
        a.solve_pattern_in_place(
            &mut work.ainv_g[c],
            p,
            &mut work.support[c],
            &mut work.blocks[c],
            &mut work.mark,
            stamp,
        );
    }
    // Coupling groups: wheels touching a common block.
    let update = work.next_stamp();
    work.parent.clear();
    work.parent.extend(0..k);
    for c in 0..k {
        for &b in &work.blocks[c] {
            let (seen, first) = work.first[b];
            if seen == update {
                let (ra, rb) = (find(&mut work.parent, c), find(&mut work.parent, first));
                if ra != rb {
                    work.parent[ra.max(rb)] = ra.min(rb);
                }
            } else {
                work.first[b] = (update, c);
            }
        }
    }
    // Group the wheels (stable: by root, then position; roots are the smallest member).
    work.order.clear();
    work.group_start.clear();
    for c in 0..k {
        let root = find(&mut work.parent, c);
        work.parent[c] = root;
    }
    for root in 0..k {
        if work.parent[root] != root {
            continue;
        }
        work.group_start.push(work.order.len());
        for c in root..k {
            if work.parent[c] == root {
                work.order.push(c);
            }
        }
    }
    work.group_start.push(k);
    // vᵀx over the pattern (v is zero elsewhere).
    let v_dot = |c: usize, y: &[f64]| -> f64 {
        let vc = v[active[c]].as_ref();
        pattern[active[c]]
            .as_ref()
            .iter()
            .map(|&i| vc[i] * y[i])
            .sum()
    };
    for g in 0..work.group_start.len() - 1 {
        let members = &work.order[work.group_start[g]..work.group_start[g + 1]];
        let kg = members.len();
        if kg == 1 {
            // Sherman–Morrison: ΔF = (vᵀy + δ̃)/(1/k_c + s vᵀA⁻¹ĝ) = k_c(vᵀy + δ̃)/(1 + λ).
            let c = members[0];
            let den = compliance[c] + s * v_dot(c, &work.ainv_g[c]);
            if den == 0.0 || !den.is_finite() {
                return Err(SINGULAR_CAPACITANCE);
            }
            df[c] = (v_dot(c, x) + delta_tilde[c]) / den;
            continue;
        }
        let lu = lu_of_size(&mut work.lu, kg);
        let mut cap = lu.matrix_mut();
        work.rhs.clear();
        for (r, &cr) in members.iter().enumerate() {
            for (q, &cq) in members.iter().enumerate() {
                let diag = if r == q { compliance[cr] } else { 0.0 };
                cap[(r, q)] = diag + s * v_dot(cr, &work.ainv_g[cq]);
            }
            work.rhs.push(v_dot(cr, x) + delta_tilde[cr]);
        }
        if !lu.factor() {
            return Err(SINGULAR_CAPACITANCE);
        }
        lu.solve_in_place(&mut work.rhs);
        for (r, &cr) in members.iter().enumerate() {
            df[cr] = work.rhs[r];
        }
    }
    for c in 0..k {
        let f = s * df[c];
        for &i in &work.support[c] {
            x[i] -= f * work.ainv_g[c][i];
        }
    }
    Ok(())
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
