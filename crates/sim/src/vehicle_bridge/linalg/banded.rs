//! Sparse and banded forms of a multibody vehicle's dense block of the step matrix A
//! (module [`super`]).
//!
//! An articulated rake of n bodies is a chain: body j is coupled only to bogies j and j + 1,
//! a bogie only to its wheelsets, so its 6n + 4 DOFs, ordered along the chain, give a matrix
//! of half-bandwidth p ≈ 5 whatever n. The ordering is found from the block's non-zeros by
//! the reverse Cuthill–McKee algorithm (Cuthill & McKee 1969; Saad, *Iterative Methods for
//! Sparse Linear Systems*, §3.3; references.md §R4.5), so nothing depends on how the vehicle
//! numbers its DOFs. The block is then factorised once per step size by an LU factorisation of
//! the band without pivoting (Golub & Van Loan, §4.3, band Gaussian elimination; references.md
//! §R4.5): A = c_M M + c_C C + c_K K with symmetric positive definite M and symmetric positive
//! semi-definite C and K is symmetric positive definite, for which elimination without
//! pivoting is stable (Golub & Van Loan §4.2). Cost O(m p²) to factorise and O(m p) per solve
//! instead of O(m²) for the dense inverse. The factorisation is checked against the dense
//! inverse on one right-hand side and refused (the dense inverse is then used) if they differ
//! by more than 1e-10 (relative).
//!
//! [`SparseRows`] stores the block's non-zeros row by row in column order, so that `A x` sums
//! the same non-zero products in the same order as the dense row (bit-identical).

/// Relative agreement required between the banded solve and the dense inverse.
const ACCEPT: f64 = 1e-10;

/// Right-hand sides solved together by [`BandedLu::solve_interleaved`] (the wheels of a rake on a
/// span are usually fewer).
pub const MANY: usize = 8;

/// The non-zeros of a row-major m × m block, row by row in column order.
#[derive(Debug, Clone, Default)]
pub struct SparseRows {
    /// Row r's entries are `start[r]..start[r + 1]` of `cols` and `vals`.
    start: Vec<usize>,
    cols: Vec<usize>,
    vals: Vec<f64>,
}

impl SparseRows {
    /// The non-zeros of the row-major m × m `entries`.
    pub fn new(entries: &[f64], m: usize) -> Self {
        let mut rows = Self::default();
        rows.start.push(0);
        for row in entries.chunks_exact(m) {
            for (c, &v) in row.iter().enumerate() {
                if v != 0.0 {
                    rows.cols.push(c);
                    rows.vals.push(v);
                }
            }
            rows.start.push(rows.cols.len());
        }
        rows
    }

    /// The number of non-zeros.
    pub fn nonzeros(&self) -> usize {
        self.vals.len()
    }

    /// `out_r = Σ_c B_rc x_c` over the non-zeros in column order (the dense row sum without
    /// its zero terms: the same value bit for bit, as adding ±0 changes no finite sum but −0).
    pub fn times(&self, x: &[f64], out: &mut [f64]) {
        for (r, o) in out.iter_mut().enumerate() {
            let (a, b) = (self.start[r], self.start[r + 1]);
            *o = self.cols[a..b]
                .iter()
                .zip(&self.vals[a..b])
                .fold(0.0, |s, (&c, v)| s + v * x[c]);
        }
    }
}

/// The band LU factors of a block in reverse Cuthill–McKee order.
#[derive(Debug, Clone, Default)]
pub struct BandedLu {
    /// `order[k]`: the block position at band position k; `pos` the inverse permutation.
    order: Vec<usize>,
    pos: Vec<usize>,
    /// Half-bandwidth p.
    p: usize,
    /// The band of the matrix itself (same layout as `lu`), kept for
    /// [`Self::refactor_with_diagonal`], and its largest entry.
    band: Vec<f64>,
    scale: f64,
    /// Row k of L (unit diagonal, not stored) and U holds columns k − p … k + p at
    /// `k (2p + 1) + (j + p − k)`.
    lu: Vec<f64>,
    /// 1/u_kk.
    inv_pivot: Vec<f64>,
}

impl BandedLu {
    /// The band factorisation of the row-major m × m `entries`, if it is worth it (the band
    /// solve costs at most a quarter of the dense one) and agrees with `inverse` (row-major,
    /// the dense inverse) to 1e-10 (relative) on one right-hand side; otherwise `None`.
    pub fn new(entries: &[f64], inverse: &[f64], m: usize) -> Option<Self> {
        let order = reverse_cuthill_mckee(entries, m);
        let mut pos = vec![0; m];
        for (k, &r) in order.iter().enumerate() {
            pos[r] = k;
        }
        let mut p = 0;
        for (r, row) in entries.chunks_exact(m).enumerate() {
            for (c, &v) in row.iter().enumerate() {
                if v != 0.0 {
                    p = p.max(pos[r].abs_diff(pos[c]));
                }
            }
        }
        if 4 * (2 * p + 1) > m {
            return None;
        }
        let w = 2 * p + 1;
        let mut lu = vec![0.0; m * w];
        for (r, row) in entries.chunks_exact(m).enumerate() {
            for (c, &v) in row.iter().enumerate() {
                if v != 0.0 {
                    lu[pos[r] * w + (pos[c] + p - pos[r])] = v;
                }
            }
        }
        let scale = entries.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        let mut banded = Self {
            order,
            pos,
            p,
            band: lu.clone(),
            scale,
            lu,
            inv_pivot: vec![0.0; m],
        };
        (banded.factor() && banded.agrees_with(inverse, m)).then_some(banded)
    }

    /// Factorises `lu` (holding the band of the matrix) in place; false if a pivot is zero
    /// (relative to the largest entry of the matrix) or not finite.
    fn factor(&mut self) -> bool {
        // The usual half-bandwidths with a constant p (the compiler unrolls the inner loops;
        // the same operations in the same order).
        match self.p {
            3 => self.factor_with(3),
            4 => self.factor_with(4),
            5 => self.factor_with(5),
            6 => self.factor_with(6),
            p => self.factor_with(p),
        }
    }

    #[inline(always)]
    fn factor_with(&mut self, p: usize) -> bool {
        let (m, w) = (self.order.len(), 2 * p + 1);
        let lu = &mut self.lu[..m * w];
        for k in 0..m {
            let pivot = lu[k * w + p];
            if !(pivot.is_finite() && pivot.abs() > 1e-14 * self.scale) {
                return false;
            }
            let inv = 1.0 / pivot;
            self.inv_pivot[k] = inv;
            let last = (k + p).min(m - 1);
            let (upper, lower) = lu.split_at_mut((k + 1) * w);
            // Row k's columns k + 1 … last.
            let pivot_row = &upper[k * w + p + 1..k * w + p + 1 + (last - k)];
            for (i, row) in (k + 1..=last).zip(lower.chunks_exact_mut(w)) {
                // Row i, column k, at k + p − i; columns k + 1 … last follow it.
                let at = k + p - i;
                let l = row[at] * inv;
                row[at] = l;
                if l != 0.0 {
                    for (x, &u) in row[at + 1..at + 1 + (last - k)].iter_mut().zip(pivot_row) {
                        *x -= l * u;
                    }
                }
            }
        }
        true
    }

    /// Makes `out` the factorisation of this block plus the diagonal entries `add` (pairs of
    /// block position and value added to the diagonal there), reusing `out`'s storage; false
    /// if that matrix is singular (`out` is then unusable).
    pub fn refactor_with_diagonal(&self, add: &[(usize, f64)], out: &mut BandedLu) -> bool {
        let w = 2 * self.p + 1;
        out.order.clone_from(&self.order);
        out.pos.clone_from(&self.pos);
        out.p = self.p;
        out.scale = self.scale;
        out.band.clear();
        out.lu.clone_from(&self.band);
        out.inv_pivot.resize(self.order.len(), 0.0);
        for &(r, value) in add {
            let k = self.pos[r];
            out.lu[k * w + self.p] += value;
        }
        out.factor()
    }

    /// The half-bandwidth.
    pub fn half_bandwidth(&self) -> usize {
        self.p
    }

    /// Whether the band solve of a right-hand side of varied entries agrees with the dense
    /// inverse to [`ACCEPT`] (relative to the largest entry of the solution).
    fn agrees_with(&self, inverse: &[f64], m: usize) -> bool {
        let b: Vec<f64> = (0..m).map(|i| 1.0 + 0.37 * (i % 7) as f64).collect();
        let dense: Vec<f64> = inverse
            .chunks_exact(m)
            .map(|row| row.iter().zip(&b).map(|(a, x)| a * x).sum())
            .collect();
        let mut x = b;
        let mut buf = vec![0.0; m];
        self.solve(&mut x, &mut buf);
        let size = dense.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        x.iter()
            .zip(&dense)
            .all(|(a, d)| (a - d).abs() <= ACCEPT * size)
    }

    /// `x ← B⁻¹ x` for the block-local `x` (block order, length m); `buf` (length ≥ m) is
    /// scratch.
    pub fn solve(&self, x: &mut [f64], buf: &mut [f64]) {
        let m = self.order.len();
        let y = &mut buf[..m];
        for (yk, &r) in y.iter_mut().zip(&self.order) {
            *yk = x[r];
        }
        match self.p {
            3 => self.substitute(3, y),
            4 => self.substitute(4, y),
            5 => self.substitute(5, y),
            6 => self.substitute(6, y),
            p => self.substitute(p, y),
        }
        for (yk, &r) in y.iter().zip(&self.order) {
            x[r] = *yk;
        }
    }

    /// The block position of each band position: right-hand sides gathered in this order
    /// (`y[k g + r]` = right-hand side r at block position `order()[k]`) suit
    /// [`Self::solve_interleaved`].
    pub fn order(&self) -> &[usize] {
        &self.order
    }

    /// `y_r ← B⁻¹ y_r` for `g` ≤ [`MANY`] right-hand sides in band order, interleaved
    /// (entry `k g + r`, gathered by [`Self::order`]): the same operations in the same order
    /// as [`Self::solve`] on each (bit for bit), with the independent sums of the right-hand
    /// sides interleaved, so that a row's substitutions do not wait on each other (one solve is
    /// a chain of dependent multiply–adds through all m rows, bound by their latency).
    pub fn solve_interleaved(&self, y: &mut [f64], g: usize) {
        match g {
            1 => self.substitute_many::<1>(y),
            2 => self.substitute_many::<2>(y),
            3 => self.substitute_many::<3>(y),
            4 => self.substitute_many::<4>(y),
            5 => self.substitute_many::<5>(y),
            6 => self.substitute_many::<6>(y),
            7 => self.substitute_many::<7>(y),
            _ => self.substitute_many::<MANY>(y),
        }
    }

    /// [`Self::substitute`] of `G` ≤ [`MANY`] interleaved right-hand sides `y` (entry
    /// `k G + r`), with the usual half-bandwidths constant (the compiler unrolls the loops).
    fn substitute_many<const G: usize>(&self, y: &mut [f64]) {
        match self.p {
            3 => self.substitute_interleaved::<G>(3, y),
            4 => self.substitute_interleaved::<G>(4, y),
            5 => self.substitute_interleaved::<G>(5, y),
            6 => self.substitute_interleaved::<G>(6, y),
            p => self.substitute_interleaved::<G>(p, y),
        }
    }

    /// [`Self::substitute`] of each of the `G` interleaved right-hand sides: its forward
    /// substitution from its own first non-zero, its sums in the same order.
    #[inline(always)]
    fn substitute_interleaved<const G: usize>(&self, p: usize, y: &mut [f64]) {
        let (m, w) = (y.len() / G, 2 * p + 1);
        let lu = &self.lu[..m * w];
        let mut start = [m; G];
        for (r, s) in start.iter_mut().enumerate() {
            *s = (0..m).position(|k| y[k * G + r] != 0.0).unwrap_or(m);
        }
        let lo = start.iter().copied().min().unwrap_or(m);
        let hi = start.iter().copied().max().unwrap_or(m);
        let row = |y: &[f64], k: usize| -> [f64; G] {
            let mut a = [0.0; G];
            a.copy_from_slice(&y[k * G..(k + 1) * G]);
            a
        };
        for k in lo..m {
            let first = k.saturating_sub(p);
            if first >= hi {
                // Every right-hand side sums over the whole row: j = k − p … k − 1.
                let mut acc = row(y, k);
                for j in first..k {
                    let l = lu[k * w + j + p - k];
                    let yj = row(y, j);
                    for r in 0..G {
                        acc[r] -= l * yj[r];
                    }
                }
                y[k * G..(k + 1) * G].copy_from_slice(&acc);
            } else {
                for r in 0..G {
                    if k < start[r] {
                        continue;
                    }
                    let mut s = y[k * G + r];
                    for j in first.max(start[r])..k {
                        s -= lu[k * w + j + p - k] * y[j * G + r];
                    }
                    y[k * G + r] = s;
                }
            }
        }
        for k in (0..m).rev() {
            let last = (k + p).min(m - 1);
            let mut acc = row(y, k);
            for j in k + 1..=last {
                let u = lu[k * w + p + (j - k)];
                let yj = row(y, j);
                for r in 0..G {
                    acc[r] -= u * yj[r];
                }
            }
            let inv = self.inv_pivot[k];
            for (yk, a) in y[k * G..(k + 1) * G].iter_mut().zip(acc) {
                *yk = a * inv;
            }
        }
    }

    /// `y ← U⁻¹ L⁻¹ y` in band order. The forward substitution starts at the first non-zero
    /// of y (before it y stays exactly zero: a wheel's vector has one non-zero in the block).
    #[inline(always)]
    fn substitute(&self, p: usize, y: &mut [f64]) {
        let (m, w) = (y.len(), 2 * p + 1);
        let lu = &self.lu[..m * w];
        let start = y.iter().position(|&v| v != 0.0).unwrap_or(m);
        for k in start..m {
            let first = k.saturating_sub(p).max(start);
            let (done, rest) = y.split_at_mut(k);
            let row = &lu[k * w + first + p - k..k * w + p];
            let mut s = rest[0];
            for (&l, &yj) in row.iter().zip(&done[first..]) {
                s -= l * yj;
            }
            rest[0] = s;
        }
        for k in (0..m).rev() {
            let last = (k + p).min(m - 1);
            let (head, solved) = y.split_at_mut(k + 1);
            let row = &lu[k * w + p + 1..k * w + p + 1 + (last - k)];
            let mut s = head[k];
            for (&u, &yj) in row.iter().zip(&solved[..last - k]) {
                s -= u * yj;
            }
            head[k] = s * self.inv_pivot[k];
        }
    }
}

/// The reverse Cuthill–McKee ordering of smallest bandwidth of the non-zero pattern of the
/// row-major m × m `entries` (symmetrised): breadth-first from a start vertex, the neighbours
/// of each vertex visited by increasing degree (then index), each further connected component
/// from its vertex of least degree, the whole order reversed; tried from every start vertex
/// (O(m · non-zeros), once per step size) and the first of least bandwidth kept (a
/// pseudo-peripheral start is what the usual heuristics look for; trying all of them is
/// affordable at these sizes). `order[k]` is the vertex at position k.
fn reverse_cuthill_mckee(entries: &[f64], m: usize) -> Vec<usize> {
    let mut adjacency = vec![Vec::new(); m];
    for r in 0..m {
        for c in 0..m {
            if r != c && (entries[r * m + c] != 0.0 || entries[c * m + r] != 0.0) {
                adjacency[r].push(c);
            }
        }
    }
    let degree: Vec<usize> = adjacency.iter().map(Vec::len).collect();
    for list in &mut adjacency {
        list.sort_by_key(|&c| (degree[c], c));
    }
    let mut best: Option<(usize, Vec<usize>)> = None;
    let mut visited = vec![false; m];
    let mut pos = vec![0; m];
    for start in 0..m {
        visited.fill(false);
        let mut order = Vec::with_capacity(m);
        let mut next = Some(start);
        while let Some(first) = next {
            visited[first] = true;
            let mut head = order.len();
            order.push(first);
            while head < order.len() {
                let v = order[head];
                head += 1;
                for &c in &adjacency[v] {
                    if !visited[c] {
                        visited[c] = true;
                        order.push(c);
                    }
                }
            }
            next = (0..m)
                .filter(|&v| !visited[v])
                .min_by_key(|&v| (degree[v], v));
        }
        order.reverse();
        for (k, &v) in order.iter().enumerate() {
            pos[v] = k;
        }
        let width = (0..m)
            .flat_map(|v| adjacency[v].iter().map(move |&c| (v, c)))
            .map(|(v, c)| pos[v].abs_diff(pos[c]))
            .max()
            .unwrap_or(0);
        if best.as_ref().is_none_or(|(w, _)| width < *w) {
            best = Some((width, order));
        }
    }
    best.map(|(_, order)| order).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A symmetric positive definite chain matrix of `n` links (tridiagonal in a shuffled
    /// numbering: vertex i sits at position (7 i) mod m, m prime to 7).
    fn shuffled_chain(m: usize) -> Vec<f64> {
        let at = |i: usize| (7 * i) % m;
        let mut a = vec![0.0; m * m];
        for i in 0..m {
            a[at(i) * m + at(i)] = 4.0 + 0.1 * i as f64;
            if i + 1 < m {
                let v = -1.0 - 0.01 * i as f64;
                a[at(i) * m + at(i + 1)] = v;
                a[at(i + 1) * m + at(i)] = v;
            }
        }
        a
    }

    /// The Gauss–Jordan inverse (the dense reference).
    fn inverse(a: &[f64], m: usize) -> Vec<f64> {
        super::super::block_diagonal::gauss_jordan_inverse(a, m).unwrap()
    }

    #[test]
    fn reverse_cuthill_mckee_finds_the_chain() {
        let m = 40;
        let a = shuffled_chain(m);
        let order = reverse_cuthill_mckee(&a, m);
        let mut seen = order.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..m).collect::<Vec<_>>());
        // A wrong inverse is refused by the check against it.
        assert!(BandedLu::new(&a, &vec![0.0; m * m], m).is_none());
        let lu = BandedLu::new(&a, &inverse(&a, m), m).unwrap();
        assert_eq!(lu.half_bandwidth(), 1);
    }

    #[test]
    fn sparse_rows_equal_the_dense_product_bit_for_bit() {
        let m = 23;
        let a = shuffled_chain(m);
        let x: Vec<f64> = (0..m).map(|i| (i as f64 * 0.77).sin()).collect();
        let mut out = vec![0.0; m];
        SparseRows::new(&a, m).times(&x, &mut out);
        for r in 0..m {
            let dense: f64 = a[r * m..(r + 1) * m]
                .iter()
                .zip(&x)
                .map(|(v, x)| v * x)
                .sum();
            assert_eq!(out[r].to_bits(), dense.to_bits());
        }
        assert_eq!(SparseRows::new(&a, m).nonzeros(), 3 * m - 2);
    }

    /// A symmetric positive definite band matrix of half-bandwidth `p` (random-ish entries,
    /// diagonally dominant) in a shuffled numbering.
    fn shuffled_band(m: usize, p: usize) -> Vec<f64> {
        let at = |i: usize| (7 * i) % m;
        let mut a = vec![0.0; m * m];
        for i in 0..m {
            a[at(i) * m + at(i)] = 4.0 * p as f64 + (i as f64 * 0.31).sin();
            for j in i + 1..(i + p + 1).min(m) {
                let v = -0.5 - 0.4 * ((i * 13 + j * 7) as f64).cos();
                a[at(i) * m + at(j)] = v;
                a[at(j) * m + at(i)] = v;
            }
        }
        a
    }

    /// `x_r ← B⁻¹ x_r` for the `nr` block-local right-hand sides `xs` (row r at
    /// `r m .. (r + 1) m`), gathered into band order in groups of up to [`MANY`] and solved by
    /// [`BandedLu::solve_interleaved`] (as `low_rank::folding` does); `buf` (length ≥ [`MANY`] m).
    fn solve_many(lu: &BandedLu, xs: &mut [f64], nr: usize, buf: &mut [f64]) {
        let order = lu.order();
        let m = order.len();
        for group in xs[..nr * m].chunks_mut(MANY * m) {
            let g = group.len() / m;
            let y = &mut buf[..g * m];
            for (r, x) in group.chunks_exact(m).enumerate() {
                for (k, &o) in order.iter().enumerate() {
                    y[k * g + r] = x[o];
                }
            }
            lu.solve_interleaved(y, g);
            for (r, x) in group.chunks_exact_mut(m).enumerate() {
                for (k, &o) in order.iter().enumerate() {
                    x[o] = y[k * g + r];
                }
            }
        }
    }

    /// Many right-hand sides solved together equal the solves one by one bit for bit:
    /// unit vectors at varied positions (a wheel's right-hand side), vectors non-zero from
    /// varied positions on, a zero vector, 1 … 19 of them (groups of [`MANY`] and a
    /// remainder), band matrices of half-bandwidths 3, 5, 7.
    #[test]
    fn solve_many_equals_solve_bit_for_bit() {
        for (m, p) in [(41, 3), (67, 5), (90, 7)] {
            let a = shuffled_band(m, p);
            let lu = BandedLu::new(&a, &inverse(&a, m), m).unwrap();
            // (The ordering found need not have bandwidth p exactly.)
            assert!(lu.half_bandwidth() >= p, "{}", lu.half_bandwidth());
            for nr in 1..20 {
                let mut xs = vec![0.0; nr * m];
                for (r, x) in xs.chunks_exact_mut(m).enumerate() {
                    match r % 3 {
                        0 => x[(r * 11 + 5) % m] = 1.0 + r as f64,
                        1 => x
                            .iter_mut()
                            .enumerate()
                            .skip(r % m)
                            .for_each(|(i, v)| *v = ((i * r) as f64 * 0.7).sin()),
                        _ if r == 5 => {}
                        _ => x[m - 1 - r % m] = -2.5,
                    }
                }
                let mut one = xs.clone();
                let mut buf = vec![0.0; m];
                for x in one.chunks_exact_mut(m) {
                    lu.solve(x, &mut buf);
                }
                let mut buf = vec![0.0; MANY * m];
                solve_many(&lu, &mut xs, nr, &mut buf);
                for (i, (a, b)) in xs.iter().zip(&one).enumerate() {
                    assert_eq!(
                        a.to_bits(),
                        b.to_bits(),
                        "m {m}, p {p}, {nr} sides, entry {i}"
                    );
                }
            }
        }
    }

    #[test]
    fn a_dense_block_is_not_banded() {
        let m = 20;
        let mut a = vec![0.5; m * m];
        for i in 0..m {
            a[i * m + i] = 2.0 * m as f64;
        }
        assert!(BandedLu::new(&a, &inverse(&a, m), m).is_none());
    }
}
