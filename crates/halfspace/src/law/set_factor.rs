//! A dense Cholesky factor A_CC = L Lᵀ of the influence matrix on a contact set, kept across
//! set changes by appending and deleting elements (references.md §C8.4, "Set changes by the
//! factor").
//!
//! The influence matrix of a uniform grid is a two-level Toeplitz matrix, A_ef = K(|ix_e −
//! ix_f|, |iy_e − iy_f|) (the half-space response to a uniform pressure on a rectangle is even
//! in both offsets), so the entries of A_CC come from the kernel table K of one convolution.
//!
//! * **Append** an element j: L l = a_Cj (forward substitution), L_jj = √(A_jj − lᵀl): O(m²)
//!   for a factor of order m.
//! * **Delete** the element in row k: with L = \[\[L₁₁, 0, 0\], \[l₂₁ᵀ, l₂₂, 0\], \[L₃₁, l₃₂,
//!   L₃₃\]\] the factor of A without row and column k is \[\[L₁₁, 0\], \[L₃₁, L̃₃₃\]\] with
//!   L̃₃₃ L̃₃₃ᵀ = L₃₃ L₃₃ᵀ + l₃₂ l₃₂ᵀ, a rank-one update by Givens rotations (references.md
//!   §C8.4): O((m − k)²).
//! * **Solve** A_CC y = b: L z = b, Lᵀ y = z, 2 m² flops, exact to round-off.
//!
//! A set change by r elements costs O(r m²) instead of the O(m³/3) of a new factorization;
//! [`SetFactor::sync`] refactors from scratch when the deletions would cost more.

use crate::error::ContactError;

/// Position of an element outside the set.
const OUTSIDE: usize = usize::MAX;

/// The factor (module documentation). L is stored column-major with a leading dimension
/// `stride` ≥ its order: L_ij (i ≥ j) at `l[j * stride + i]`.
#[derive(Debug)]
pub(super) struct SetFactor {
    /// K(dx, dy) at `dy * nx + dx` \[m/Pa\].
    kernel: Vec<f64>,
    nx: usize,
    /// The element of each row of the factor.
    members: Vec<usize>,
    /// Its grid cell (column, row), kept beside `members` so that the influence row of an
    /// appended element needs no integer divisions.
    cells: Vec<(u32, u32)>,
    /// The row of each element ([`OUTSIDE`] when not in the set).
    position: Vec<usize>,
    l: Vec<f64>,
    stride: usize,
    /// Scratch of the order of the factor.
    work: Vec<f64>,
    /// Scratch of [`Self::sync`]: rows leaving; (key, element) entering.
    leaving: Vec<usize>,
    entering: Vec<(f64, usize)>,
}

impl SetFactor {
    /// An empty factor for a grid of `nx` columns with the kernel table `kernel`
    /// (`kernel[dy * nx + dx]` = the displacement at offset (dx, dy) ≥ 0 of a unit pressure on
    /// one element).
    pub(super) fn new(kernel: Vec<f64>, nx: usize) -> Self {
        let n = kernel.len();
        SetFactor {
            kernel,
            nx,
            members: Vec::new(),
            cells: Vec::new(),
            position: vec![OUTSIDE; n],
            l: Vec::new(),
            stride: 0,
            work: Vec::new(),
            leaving: Vec::new(),
            entering: Vec::new(),
        }
    }

    /// The kernel table K(dx, dy) at `dy * nx + dx` \[m/Pa\].
    pub(super) fn kernel(&self) -> &[f64] {
        &self.kernel
    }

    /// The elements of the set in the order of the factor's rows.
    pub(super) fn members(&self) -> &[usize] {
        &self.members
    }

    /// The grid cell (column, row) of element `e`.
    fn cell(&self, e: usize) -> (u32, u32) {
        ((e % self.nx) as u32, (e / self.nx) as u32)
    }

    /// Makes the set equal to `{e : in_contact[e]}`: deletes the elements that left (the
    /// latest rows first), or refactors from scratch when the deletions would cost more
    /// (Σ (m − k)² over the rows k deleted against (m − r)³/6), then appends the elements
    /// that entered, innermost first (by their distance from the set's centroid relative to
    /// its extent), so that the rows most likely to leave next are the last, cheapest ones.
    pub(super) fn sync(&mut self, in_contact: &[bool]) -> Result<(), ContactError> {
        let m = self.members.len();
        let mut leaving = std::mem::take(&mut self.leaving);
        leaving.clear();
        leaving.extend((0..m).rev().filter(|&k| !in_contact[self.members[k]]));
        let delete_cost: f64 = leaving.iter().map(|&k| ((m - k) as f64).powi(2)).sum();
        if delete_cost > ((m - leaving.len()) as f64).powi(3) / 6.0 {
            for &e in &self.members {
                self.position[e] = OUTSIDE;
            }
            self.members.clear();
            self.cells.clear();
        } else {
            for &k in &leaving {
                self.delete(k);
            }
        }
        self.leaving = leaving;
        let mut entering = std::mem::take(&mut self.entering);
        entering.clear();
        let nx = self.nx;
        let (mut count, mut cx, mut cy) = (0.0, 0.0, 0.0);
        let (mut x0, mut x1, mut y0, mut y1) = (usize::MAX, 0, usize::MAX, 0);
        for (e, _) in in_contact.iter().enumerate().filter(|(_, c)| **c) {
            let (ix, iy) = (e % nx, e / nx);
            count += 1.0;
            cx += ix as f64;
            cy += iy as f64;
            (x0, x1, y0, y1) = (x0.min(ix), x1.max(ix), y0.min(iy), y1.max(iy));
            if self.position[e] == OUTSIDE {
                entering.push((0.0, e));
            }
        }
        if entering.len() > 1 {
            let (cx, cy) = (cx / count, cy / count);
            let (hx, hy) = (0.5 + (x1 - x0) as f64, 0.5 + (y1 - y0) as f64);
            for (key, e) in entering.iter_mut() {
                let (dx, dy) = (((*e % nx) as f64 - cx) / hx, ((*e / nx) as f64 - cy) / hy);
                *key = dx * dx + dy * dy;
            }
            entering.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        }
        let result = entering.iter().try_for_each(|&(_, e)| self.append(e));
        self.entering = entering;
        result
    }

    /// Grows the storage to hold a factor of order `order`, keeping the current one.
    fn reserve(&mut self, order: usize) {
        if order <= self.stride {
            return;
        }
        let m = self.members.len();
        let stride = order
            .max(2 * self.stride)
            .min(self.position.len())
            .max(order);
        let mut l = vec![0.0; stride * stride];
        for j in 0..m {
            l[j * stride + j..j * stride + m]
                .copy_from_slice(&self.l[j * self.stride + j..j * self.stride + m]);
        }
        self.l = l;
        self.stride = stride;
    }

    /// Appends element `e` as the last row (module documentation).
    fn append(&mut self, e: usize) -> Result<(), ContactError> {
        let m = self.members.len();
        self.reserve(m + 1);
        let s = self.stride;
        let mut a = std::mem::take(&mut self.work);
        a.clear();
        // A_fe = K(|ix_f − ix_e|, |iy_f − iy_e|) for every member f.
        let (ex, ey) = self.cell(e);
        let (kernel, nx) = (&self.kernel, self.nx);
        a.extend(
            self.cells
                .iter()
                .map(|&(fx, fy)| kernel[fy.abs_diff(ey) as usize * nx + fx.abs_diff(ex) as usize]),
        );
        // Forward substitution L l = a (l overwrites a).
        substitute_fast(&self.l, s, m, &mut a[..], false);
        let diag = self.kernel[0];
        let d2 = diag - a.iter().map(|v| v * v).sum::<f64>();
        // A NaN pivot fails too.
        if d2.is_nan() || d2 <= 1e-12 * diag {
            self.work = a;
            return Err(ContactError::InvalidParameter {
                name: "influence matrix on the contact set",
                value: d2 / diag,
                reason: "must be positive definite (Cholesky pivot)",
            });
        }
        for (j, &lj) in a.iter().enumerate() {
            self.l[j * s + m] = lj;
        }
        self.l[m * s + m] = d2.sqrt();
        self.work = a;
        self.position[e] = m;
        self.members.push(e);
        self.cells.push((ex, ey));
        Ok(())
    }

    /// Deletes row and column `k` (module documentation).
    fn delete(&mut self, k: usize) {
        let (m, s) = (self.members.len(), self.stride);
        // x = l₃₂ (column k below the diagonal); L₃₃ L₃₃ᵀ + x xᵀ by Givens rotations.
        let mut x = std::mem::take(&mut self.work);
        x.clear();
        x.extend_from_slice(&self.l[k * s + k + 1..k * s + m]);
        rotate_fast(&mut self.l, s, k, m, &mut x);
        self.work = x;
        // Remove row k from the columns before it, and shift the later columns left and up.
        for j in 0..k {
            self.l.copy_within(j * s + k + 1..j * s + m, j * s + k);
        }
        for j in k + 1..m {
            self.l
                .copy_within(j * s + j..j * s + m, (j - 1) * s + j - 1);
        }
        let e = self.members.remove(k);
        self.cells.remove(k);
        self.position[e] = OUTSIDE;
        for &f in &self.members[k..] {
            self.position[f] -= 1;
        }
    }

    /// Y = A_CC⁻¹ B in place for one (`f64`) or several (`[f64; K]`) right-hand sides
    /// (`y[i]` holds row i of B on entry, in the order of [`Self::members`]): one pass over
    /// the factor for all of them.
    pub(super) fn solve_block<T: Row>(&self, y: &mut [T]) {
        let (m, s) = (self.members.len(), self.stride);
        substitute_fast(&self.l, s, m, y, true);
    }
}

/// Runs `$body` (a block using the listed arguments) through a copy compiled with AVX and FMA
/// when the processor has both: the same operations in the same order as without. The
/// multiply-adds of [`Row`] are fused (`f64::mul_add`, one rounding), in hardware here and
/// by the exactly rounded software `fma` of the plain build, so the results are identical
/// bit for bit, only slower without FMA. The body must be a plain function call chain
/// (closures would not inherit the target features).
macro_rules! avx_dispatch {
    ($(#[$doc:meta])* fn $name:ident $(<$g:ident: $b:path>)?($($arg:ident: $ty:ty),*) $body:block) => {
        $(#[$doc])*
        fn $name $(<$g: $b>)?($($arg: $ty),*) {
            #[cfg(target_arch = "x86_64")]
            {
                #[target_feature(enable = "avx,fma")]
                fn avx $(<$g: $b>)?($($arg: $ty),*) $body
                if std::arch::is_x86_feature_detected!("avx")
                    && std::arch::is_x86_feature_detected!("fma")
                {
                    // SAFETY: AVX and FMA are present (checked at run time just above).
                    unsafe { avx($($arg),*) };
                    return;
                }
            }
            $body
        }
    };
}

avx_dispatch! {
    /// [`substitute`], with AVX and FMA when the processor has them.
    fn substitute_fast<T: Row>(l: &[f64], s: usize, m: usize, y: &mut [T], backward: bool) {
        substitute(l, s, m, y, backward)
    }
}

avx_dispatch! {
    /// The Givens rotations of a deletion (row and column `k` of a factor of order `m`,
    /// [`SetFactor::delete`]): L₃₃ L₃₃ᵀ + x xᵀ with x = l₃₂ (overwritten), with AVX when the
    /// processor has it (and FMA; the rotations use no fused multiply-add).
    fn rotate_fast(l: &mut [f64], s: usize, k: usize, m: usize, x: &mut [f64]) {
        for j in k + 1..m {
            let xj = x[j - k - 1];
            let col = &mut l[j * s..j * s + m];
            let ljj = col[j];
            let r = ljj.hypot(xj);
            let (c, sn) = (r / ljj, xj / ljj);
            col[j] = r;
            for (lij, xi) in col[j + 1..m].iter_mut().zip(&mut x[j - k..]) {
                *lij = (*lij + sn * *xi) / c;
                *xi = c * *xi - sn * *lij;
            }
        }
    }
}

/// Forward substitution L z = b in place (column by column: z_j = b_j / L_jj, then
/// b_i −= L_ij z_j for i > j), and with `backward` the back substitution Lᵀ y = z
/// (y_j = (z_j − Σ_{i>j} L_ij y_i) / L_jj). L column-major with leading dimension `s`.
#[inline(always)]
fn substitute<T: Row>(l: &[f64], s: usize, m: usize, y: &mut [T], backward: bool) {
    // Four columns per pass over the rows below them: each y_i takes the four updates in
    // column order, as the plain loop does (the same results bit for bit), with one load
    // and store of y_i instead of four.
    let mut start = 0;
    while start + 4 <= m {
        let j = start;
        let mut yc = [y[j]; 4];
        for c in 0..4 {
            let col = &l[(j + c) * s..(j + c) * s + j + 4];
            let v = y[j + c].scale(1.0 / col[j + c]);
            y[j + c] = v;
            yc[c] = v;
            for (yi, &lic) in y[j + c + 1..j + 4].iter_mut().zip(&col[j + c + 1..j + 4]) {
                yi.sub_scaled(lic, v);
            }
        }
        let cols: [&[f64]; 4] = std::array::from_fn(|c| &l[(j + c) * s + j + 4..(j + c) * s + m]);
        for (i, yi) in y[j + 4..m].iter_mut().enumerate() {
            let mut t = *yi;
            t.sub_scaled(cols[0][i], yc[0]);
            t.sub_scaled(cols[1][i], yc[1]);
            t.sub_scaled(cols[2][i], yc[2]);
            t.sub_scaled(cols[3][i], yc[3]);
            *yi = t;
        }
        start += 4;
    }
    for j in start..m {
        let col = &l[j * s..j * s + m];
        let yj = y[j].scale(1.0 / col[j]);
        y[j] = yj;
        for (yi, &lij) in y[j + 1..m].iter_mut().zip(&col[j + 1..m]) {
            yi.sub_scaled(lij, yj);
        }
    }
    if backward {
        for j in (0..m).rev() {
            let col = &l[j * s..j * s + m];
            let sum = T::dot(&col[j + 1..m], &y[j + 1..m]);
            y[j] = y[j].minus(sum).scale(1.0 / col[j]);
        }
    }
}

/// A row of right-hand sides: one value or `K`.
pub(super) trait Row: Copy {
    /// self × by.
    fn scale(self, by: f64) -> Self;
    /// self − other.
    fn minus(self, other: Self) -> Self;
    /// self −= l y, fused (one rounding: `f64::mul_add`).
    fn sub_scaled(&mut self, l: f64, y: Self);
    /// Σ_i l_i y_i, by fused multiply-adds.
    fn dot(l: &[f64], y: &[Self]) -> Self;
}

impl Row for f64 {
    #[inline(always)]
    fn scale(self, by: f64) -> Self {
        self * by
    }
    #[inline(always)]
    fn minus(self, other: Self) -> Self {
        self - other
    }
    #[inline(always)]
    fn sub_scaled(&mut self, l: f64, y: Self) {
        *self = (-l).mul_add(y, *self);
    }
    /// With four partial sums (vectorisable; a fixed order).
    #[inline(always)]
    fn dot(a: &[f64], b: &[f64]) -> f64 {
        let mut acc = [0.0; 4];
        let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
        let tail = ca
            .remainder()
            .iter()
            .zip(cb.remainder())
            .fold(0.0, |t, (x, y)| x.mul_add(*y, t));
        for (x, y) in ca.zip(cb) {
            for r in 0..4 {
                acc[r] = x[r].mul_add(y[r], acc[r]);
            }
        }
        (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
    }
}

impl<const K: usize> Row for [f64; K] {
    #[inline(always)]
    fn scale(mut self, by: f64) -> Self {
        for v in &mut self {
            *v *= by;
        }
        self
    }
    #[inline(always)]
    fn minus(mut self, other: Self) -> Self {
        for (v, o) in self.iter_mut().zip(other) {
            *v -= o;
        }
        self
    }
    #[inline(always)]
    fn sub_scaled(&mut self, l: f64, y: Self) {
        for r in 0..K {
            self[r] = (-l).mul_add(y[r], self[r]);
        }
    }
    /// With four partial sums per lane (four independent chains of additions, so the loop
    /// is not bound by the latency of one; a fixed order).
    #[inline(always)]
    fn dot(l: &[f64], y: &[Self]) -> Self {
        let mut acc = [[0.0; K]; 4];
        let (cl, cy) = (l.chunks_exact(4), y.chunks_exact(4));
        let mut tail = [0.0; K];
        for (li, yi) in cl.remainder().iter().zip(cy.remainder()) {
            for r in 0..K {
                tail[r] = li.mul_add(yi[r], tail[r]);
            }
        }
        for (l4, y4) in cl.zip(cy) {
            for (a, (li, yi)) in acc.iter_mut().zip(l4.iter().zip(y4)) {
                for r in 0..K {
                    a[r] = li.mul_add(yi[r], a[r]);
                }
            }
        }
        std::array::from_fn(|r| (acc[0][r] + acc[1][r]) + (acc[2][r] + acc[3][r]) + tail[r])
    }
}

#[cfg(test)]
mod tests {
    use super::SetFactor;
    use crate::grid::Grid;
    use crate::material::Material;
    use crate::normcg::NormalSolver;

    /// A 12 × 10 grid's kernel by one convolution, and the full influence matrix by a
    /// convolution per element (the FFT operator: the independent reference).
    fn setup() -> (SetFactor, Vec<Vec<f64>>, usize) {
        let grid = Grid::centred(12, 10, 1e-4, 1.3e-4, 0.0, 0.0).unwrap();
        let mut solver = NormalSolver::new(grid, Material::identical(210e9, 0.3).unwrap()).unwrap();
        let n = grid.len();
        let mut columns = Vec::new();
        for e in 0..n {
            let mut unit = vec![0.0; n];
            unit[e] = 1.0;
            let mut u = vec![0.0; n];
            solver.displacement(&unit, &mut u).unwrap();
            columns.push(u);
        }
        (SetFactor::new(columns[0].clone(), grid.nx), columns, n)
    }

    /// Solves on the set after a sequence of set changes (appends, deletions at the start,
    /// middle and end, a refactoring) and checks A_CC y = b with the FFT operator's columns to
    /// 1e-10 relative (round-off of a factor of order ≤ 120 with condition ≈ 30).
    #[test]
    fn solves_after_appends_and_deletions() {
        let (mut factor, a, n) = setup();
        let sets: [Box<dyn Fn(usize) -> bool>; 5] = [
            Box::new(|e| e % 3 != 0),
            Box::new(|e| e % 3 != 0 && e != 1 && e != 59 && e != 118),
            Box::new(|e| (e % 3 != 0 && e != 1) || e == 30),
            Box::new(|e| e % 2 == 0),
            Box::new(|_| true),
        ];
        for set in &sets {
            let in_contact: Vec<bool> = (0..n).map(set).collect();
            factor.sync(&in_contact).unwrap();
            let members = factor.members().to_vec();
            let mut sorted = members.clone();
            sorted.sort();
            assert_eq!(
                sorted,
                (0..n).filter(|&e| in_contact[e]).collect::<Vec<_>>()
            );
            let b: Vec<f64> = members
                .iter()
                .map(|&e| 1.0 + (e as f64 * 0.37).sin())
                .collect();
            let mut y = b.clone();
            factor.solve_block(&mut y);
            // Three right-hand sides at once equal three single solves (1e-12 relative).
            let mut block: Vec<[f64; 3]> = b.iter().map(|&v| [v, 2.0 * v, -v]).collect();
            factor.solve_block(&mut block);
            for (row, yi) in block.iter().zip(&y) {
                for (r, c) in row.iter().zip([1.0, 2.0, -1.0]) {
                    assert!(
                        (r - c * yi).abs() <= 1e-12 * yi.abs().max(1e-30),
                        "{r} vs {}",
                        c * yi
                    );
                }
            }
            let scale = b.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            for (i, &e) in members.iter().enumerate() {
                let ay: f64 = members.iter().zip(&y).map(|(&f, yf)| a[f][e] * yf).sum();
                assert!((ay - b[i]).abs() <= 1e-10 * scale, "{ay} vs {}", b[i]);
            }
        }
    }
}
