//! The two-level preconditioner of the steady-rolling Newton systems
//! ([`super::NkPreconditioner::TwoLevel`]; docs/tangential.md "Performance", issue #18).
//!
//! **Coarse space.** The elements are grouped in blocks of 4 × 4; each block gives up to three
//! aggregates: its adhesion elements' d_x, their d_y, and its slip elements' dθ. P is the
//! 0/1 matrix of these aggregates (every unknown in exactly one), L the upstream line solve
//! ([`super::nk_precondition`]) and J the Newton matrix. The coarse matrix is the Galerkin
//! matrix of the line-preconditioned operator, E = Pᵀ L⁻¹ J P.
//!
//! **Projected form** (no product besides GMRES's): with z = L⁻¹ r and y = E⁻¹ Pᵀ z,
//! M r = (I − Π) z + P y, Π the projector onto the aggregate means: the coarse solution
//! replaces the mean of the line solve's output over each aggregate.
//!
//! **E without products** (formula (iv) of docs/tangential.md). With ψ_i = L⁻ᵀ P_i (marching
//! each grid row from the trailing edge), φ_i its displacement form (ψ in adhesion, ψ t in
//! slip) and g_i(p) = φ_i(p) − φ_i(p − e_x) (with A_v(δx) at offset o equal to A at
//! o + e_x, C = A − A_v telescopes):
//!
//! ```text
//! E_ij = Σ_p g_i(p)·(A f_j)(p) + Σ_{k slip} ψ_i(k) |S_k| P_j(k)
//! ```
//!
//! with f_j the traction change of aggregate j (e_x or e_y on its adhesion elements, g t on
//! its slip elements). In adhesion ψ_i is constant upstream of the block, so g_i lives on the
//! block and on the element ahead of each row's adhesion run (possibly one element beyond the
//! grid); through slip elements it decays (followed to [`CHAIN_CUT`] of its peak). The
//! entries between blocks at most [`NEAR`] apart are summed with the direct kernel A from
//! tables ([`kernel`]: A, A summed over a block, over two blocks): exact, except that the
//! traction change of a whole slip block is replaced by its mean (a model, 2 % of the near
//! part on the test case). The far field is a point-force model: the aggregate's total
//! traction F_j at its block, the field of all blocks by one FFT convolution on the grid of
//! blocks with A sampled at multiples of the block size, and each g_i summed over the blocks.
//! The D term is kept exactly for every pair. E is measured against the probed Galerkin
//! matrix in `tests.rs`.
//!
//! **Coarse solve.** [`INNER`] GMRES iterations on E, right-preconditioned by one forward
//! Gauss–Seidel sweep on its entries between blocks at most [`SWEEP_NEAR`] apart; the outer
//! iteration is flexible GMRES (references.md §C3.11), since this inner iteration changes
//! from one application to the next.

mod entries;
mod kernel;

use super::gmres::{GmresWork, LinearProblem, gmres_with};
use super::nk_precondition::{Class, NewtonSystem};
use crate::convolution::{FftConvolution, KernelSpectrum};
use crate::grid::Grid;
use crate::influence::circulant_from_centred;
use crate::operator::TangentialInfluenceOperator;
use kernel::KernelTables;

/// Block edge in elements.
const BLOCK: usize = 4;
/// Blocks at most this far apart (Chebyshev distance) have their E entries summed exactly.
const NEAR: usize = 2;
/// The sweep preconditioning the coarse solve uses the entries between blocks at most this
/// far apart.
const SWEEP_NEAR: usize = 1;
/// GMRES iterations of the coarse solve.
const INNER: usize = 5;
/// Relative residual at which the coarse solve stops early.
const INNER_TOL: f64 = 1e-3;
/// ψ_i is followed through the slip elements beyond its block until it has decayed to this
/// fraction of its largest value (the rest of the chain changes E by less).
const CHAIN_CUT: f64 = 1e-2;
/// No aggregate.
const NONE: u32 = u32::MAX;

/// The kind of an aggregate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    AdhesionX,
    AdhesionY,
    Slip,
}

const KINDS: [Kind; 3] = [Kind::AdhesionX, Kind::AdhesionY, Kind::Slip];

/// One coarse unknown.
#[derive(Debug, Clone, Copy)]
struct Aggregate {
    /// The block's column and row in the grid of blocks.
    bx: usize,
    by: usize,
    /// Whether the block lies entirely in the grid.
    inside: bool,
    kind: Kind,
    count: usize,
    /// Total traction change F_j of a unit coarse value.
    force: (f64, f64),
}

/// A point of g_i: grid column (up to nx), grid row, the vector g.
#[derive(Debug, Clone, Copy)]
struct GPoint {
    ix: usize,
    iy: usize,
    g: (f64, f64),
}

/// g_i summed over one cell of the far-field grid.
#[derive(Debug, Clone, Copy)]
struct Cell {
    /// Linear index and (column, row) of the cell.
    index: u32,
    at: (u32, u32),
    g: (f64, f64),
}

/// The coarse matrix E and its solver (module documentation). All vectors are kept between
/// Newton steps and solves of the same grid: rebuilding reuses their capacity.
pub(super) struct TwoLevel {
    nx: usize,
    ny: usize,
    nbx: usize,
    nby: usize,
    /// Columns of the grid of blocks of the far field (one more column for the points one
    /// element beyond the grid).
    ncx: usize,
    aggs: Vec<Aggregate>,
    /// Aggregate of each block and kind (NONE if absent).
    block_aggs: Vec<[u32; 3]>,
    /// Aggregate of each unknown slot (2n; NONE for exterior and unused slots).
    slot_agg: Vec<u32>,
    /// A and its block sums.
    tables: KernelTables,
    /// g_i on its own block when it is uniform there (a full adhesion block): the box part;
    /// `g_points` then holds only the points outside the block.
    g_box: Vec<Option<(f64, f64)>>,
    g_start: Vec<usize>,
    g_points: Vec<GPoint>,
    /// For each element: the column of the first element at or after it in its grid row that
    /// is not in adhesion (nx if none).
    run_end: Vec<u32>,
    /// The traction changes f_j of every aggregate: (element column, row, f).
    f_start: Vec<usize>,
    f_points: Vec<(isize, isize, (f64, f64))>,
    /// The D entries ψ_i(k) |S_k| along each ψ_i: (aggregate j, value).
    d_start: Vec<usize>,
    d_points: Vec<(u32, f64)>,
    /// g_i summed over the cells of the far-field grid: (cell, G).
    gc_start: Vec<usize>,
    gc: Vec<Cell>,
    /// Sparse rows of E: columns, exact values (near and D), exact minus the point model.
    e_start: Vec<usize>,
    e_col: Vec<u32>,
    e_val: Vec<f64>,
    e_corr: Vec<f64>,
    e_diag: Vec<f64>,
    /// The lower part of the near entries for the sweep: (column, value).
    lo_start: Vec<usize>,
    lo: Vec<(u32, f64)>,
    /// Far-field kernel A(B·Δ) on the grid of blocks (centred, for the near model) and its
    /// spectra.
    far_xx: Vec<f64>,
    far_xy: Vec<f64>,
    far_yy: Vec<f64>,
    conv: FftConvolution,
    spectra: [KernelSpectrum; 3],
    fx: Vec<f64>,
    fy: Vec<f64>,
    ux: Vec<f64>,
    uy: Vec<f64>,
    // Scratch.
    row_pos: Vec<u32>,
    cell_acc: Vec<(f64, f64)>,
    touched: Vec<usize>,
    z: Vec<f64>,
    rhs: Vec<f64>,
    y: Vec<f64>,
    work: GmresWork,
    /// Replace the slip traction changes of whole slip blocks by their mean in the near
    /// entries (the block-sum table instead of an element sum; true except in the test of
    /// the exact formula).
    slip_mean: bool,
    /// [`CHAIN_CUT`] (smaller in the test of the exact formula).
    chain_cut: f64,
    /// Whether the last build produced a usable E (every diagonal entry non-zero).
    ready: bool,
}

impl TwoLevel {
    /// Plans the far-field convolution of `op`'s grid.
    pub(super) fn new<T: TangentialInfluenceOperator>(op: &T) -> Self {
        let g = *op.grid();
        let (nx, ny) = (g.nx, g.ny);
        let nbx = nx.div_ceil(BLOCK);
        let nby = ny.div_ceil(BLOCK);
        let ncx = (nx + 1).div_ceil(BLOCK);
        let tables = KernelTables::new(op);
        let (wx, wy) = (2 * ncx - 1, 2 * nby - 1);
        let mut far = [vec![0.0; wx * wy], vec![0.0; wx * wy], vec![0.0; wx * wy]];
        let b = BLOCK as isize;
        let (lx, ly) = (nx as isize, ny as isize - 1);
        for j in 0..wy {
            let oy = ((j as isize - (nby as isize - 1)) * b).clamp(-ly, ly);
            for i in 0..wx {
                let ox = ((i as isize - (ncx as isize - 1)) * b).clamp(-lx, lx);
                let (a, c, d) = tables.a((ox, oy));
                far[0][j * wx + i] = a;
                far[1][j * wx + i] = c;
                far[2][j * wx + i] = d;
            }
        }
        let conv = FftConvolution::new(ncx, nby);
        let shape = Grid::new(ncx, nby, g.dx, g.dy, 0.0, 0.0).expect("a grid of blocks");
        let spectra =
            [0, 1, 2].map(|c| conv.kernel_spectrum(&circulant_from_centred(&shape, &far[c])));
        let [far_xx, far_xy, far_yy] = far;
        let cells = ncx * nby;
        TwoLevel {
            nx,
            ny,
            nbx,
            nby,
            ncx,
            aggs: Vec::new(),
            block_aggs: vec![[NONE; 3]; nbx * nby],
            slot_agg: vec![NONE; 2 * nx * ny],
            tables,
            g_box: Vec::new(),
            g_start: Vec::new(),
            g_points: Vec::new(),
            d_start: Vec::new(),
            d_points: Vec::new(),
            f_start: Vec::new(),
            f_points: Vec::new(),
            run_end: vec![0; nx * ny],
            gc_start: Vec::new(),
            gc: Vec::new(),
            e_start: Vec::new(),
            e_col: Vec::new(),
            e_val: Vec::new(),
            e_corr: Vec::new(),
            e_diag: Vec::new(),
            lo_start: Vec::new(),
            lo: Vec::new(),
            far_xx,
            far_xy,
            far_yy,
            conv,
            spectra,
            fx: vec![0.0; cells],
            fy: vec![0.0; cells],
            ux: vec![0.0; cells],
            uy: vec![0.0; cells],
            row_pos: Vec::new(),
            cell_acc: vec![(0.0, 0.0); cells],
            touched: Vec::new(),
            z: vec![0.0; 2 * nx * ny],
            rhs: Vec::new(),
            y: Vec::new(),
            work: GmresWork::new(0, INNER, false),
            slip_mean: true,
            chain_cut: CHAIN_CUT,
            ready: false,
        }
    }

    /// The number of coarse unknowns of the last build.
    #[cfg(test)]
    pub(super) fn coarse_len(&self) -> usize {
        self.aggs.len()
    }

    fn block_of(&self, ix: usize, iy: usize) -> usize {
        (iy / BLOCK) * self.nbx + ix / BLOCK
    }

    /// Build E for the Newton system `sys` (module documentation).
    pub(super) fn build(&mut self, sys: &NewtonSystem) {
        self.aggregates(sys);
        self.sources(sys);
        self.weights(sys);
        self.far_weights();
        self.rows();
        let m = self.aggs.len();
        self.rhs.resize(m, 0.0);
        self.y.resize(m, 0.0);
        if self.work.len() != m {
            self.work = GmresWork::new(m, INNER, false);
        }
        self.ready = m > 0 && self.e_diag.iter().all(|d| d.is_finite() && *d != 0.0);
    }

    /// Number the aggregates block by block, and the slot of each unknown.
    fn aggregates(&mut self, sys: &NewtonSystem) {
        let (nx, n) = (self.nx, self.nx * self.ny);
        self.aggs.clear();
        self.slot_agg.fill(NONE);
        let mut counts = std::mem::take(&mut self.block_aggs);
        counts.fill([0; 3]);
        for k in 0..n {
            let b = self.block_of(k % nx, k / nx);
            match sys.class[k] {
                Class::Exterior => {}
                Class::Adhesion => {
                    counts[b][0] += 1;
                    counts[b][1] += 1;
                }
                Class::Slip => counts[b][2] += 1,
            }
        }
        for (b, c) in counts.iter_mut().enumerate() {
            for (slot, kind) in KINDS.iter().enumerate() {
                let count = c[slot] as usize;
                c[slot] = if count > 0 {
                    let (bx, by) = (b % self.nbx, b / self.nbx);
                    self.aggs.push(Aggregate {
                        bx,
                        by,
                        inside: (bx + 1) * BLOCK <= self.nx && (by + 1) * BLOCK <= self.ny,
                        kind: *kind,
                        count,
                        force: (0.0, 0.0),
                    });
                    (self.aggs.len() - 1) as u32
                } else {
                    NONE
                };
            }
        }
        self.block_aggs = counts;
        for k in 0..n {
            let b = self.block_of(k % nx, k / nx);
            let ids = self.block_aggs[b];
            match sys.class[k] {
                Class::Exterior => {}
                Class::Adhesion => {
                    self.slot_agg[k] = ids[0];
                    self.slot_agg[n + k] = ids[1];
                    self.aggs[ids[0] as usize].force.0 += 1.0;
                    self.aggs[ids[1] as usize].force.1 += 1.0;
                }
                Class::Slip => {
                    self.slot_agg[k] = ids[2];
                    let f = &mut self.aggs[ids[2] as usize].force;
                    f.0 += sys.bound[k] * sys.tx[k];
                    f.1 += sys.bound[k] * sys.ty[k];
                }
            }
        }
    }

    /// The elements of each aggregate with their traction change f_j (e_x or e_y in
    /// adhesion, g t in slip).
    fn sources(&mut self, sys: &NewtonSystem) {
        let nx = self.nx;
        for row in (0..self.nx * self.ny).step_by(nx) {
            let mut end = nx as u32;
            for ix in (0..nx).rev() {
                if sys.class[row + ix] != Class::Adhesion {
                    end = ix as u32;
                }
                self.run_end[row + ix] = end;
            }
        }
        self.f_start.clear();
        self.f_points.clear();
        for j in 0..self.aggs.len() {
            self.f_start.push(self.f_points.len());
            let Aggregate { bx, by, kind, .. } = self.aggs[j];
            let (x0, y0) = (bx * BLOCK, by * BLOCK);
            for qy in y0..(y0 + BLOCK).min(self.ny) {
                for qx in x0..(x0 + BLOCK).min(self.nx) {
                    let q = qy * self.nx + qx;
                    let f = match (sys.class[q], kind) {
                        (Class::Adhesion, Kind::AdhesionX) => (1.0, 0.0),
                        (Class::Adhesion, Kind::AdhesionY) => (0.0, 1.0),
                        (Class::Slip, Kind::Slip) => {
                            (sys.bound[q] * sys.tx[q], sys.bound[q] * sys.ty[q])
                        }
                        _ => continue,
                    };
                    self.f_points.push((qx as isize, qy as isize, f));
                }
            }
        }
        self.f_start.push(self.f_points.len());
    }

    /// g_i of every aggregate (module documentation): march ψ_i = L⁻ᵀ P_i along each of
    /// the block's rows from its first column towards the leading edge.
    fn weights(&mut self, sys: &NewtonSystem) {
        let (nx, ny) = (self.nx, self.ny);
        let (dx, dy) = sys.own;
        let (bxx, bxy, byy) = sys.upstream.unwrap_or((0.0, 0.0, 0.0));
        self.g_start.clear();
        self.g_points.clear();
        self.d_start.clear();
        self.d_points.clear();
        self.g_box.clear();
        for i in 0..self.aggs.len() {
            self.g_start.push(self.g_points.len());
            self.d_start.push(self.d_points.len());
            let Aggregate { bx, by, kind, .. } = self.aggs[i];
            let ix0 = bx * BLOCK;
            for iy in by * BLOCK..((by + 1) * BLOCK).min(ny) {
                let (mut prev, mut peak) = ((0.0, 0.0), 0.0f64);
                let mut open = true;
                let mut next = ix0;
                while next < nx {
                    let ix = next;
                    let k = iy * nx + ix;
                    let (cx, cy) = (bxx * prev.0 + bxy * prev.1, bxy * prev.0 + byy * prev.1);
                    let own = ix < ix0 + BLOCK;
                    // Beyond the block, ψ is constant along an adhesion run (the upstream
                    // coupling is minus the own coefficient): jump to the run's end.
                    next = if !own && sys.class[k] == Class::Adhesion {
                        (self.run_end[k] as usize).max(ix + 1)
                    } else {
                        ix + 1
                    };
                    let phi = match sys.class[k] {
                        Class::Exterior => (0.0, 0.0),
                        Class::Adhesion => {
                            let px = f64::from(u8::from(own && kind == Kind::AdhesionX));
                            let py = f64::from(u8::from(own && kind == Kind::AdhesionY));
                            ((px - cx) / dx, (py - cy) / dy)
                        }
                        Class::Slip => {
                            let ps = f64::from(u8::from(own && kind == Kind::Slip));
                            let d = sys.slip_diagonal(k);
                            let rhs = ps - sys.bound[k] * (sys.tx[k] * cx + sys.ty[k] * cy);
                            let psi = if d > 0.0 { rhs / d } else { 0.0 };
                            if psi * sys.slip_speed[k] != 0.0 {
                                self.d_points
                                    .push((self.slot_agg[k], psi * sys.slip_speed[k]));
                            }
                            (psi * sys.tx[k], psi * sys.ty[k])
                        }
                    };
                    let g = (phi.0 - prev.0, phi.1 - prev.1);
                    let scale = phi.0.abs() + phi.1.abs() + prev.0.abs() + prev.1.abs();
                    if g.0.abs() + g.1.abs() > 1e-12 * scale {
                        self.g_points.push(GPoint { ix, iy, g });
                    }
                    prev = phi;
                    let size = prev.0.abs() + prev.1.abs();
                    peak = peak.max(size);
                    // Beyond the block: the run ended at the contact edge, or ψ has decayed
                    // through the slip elements.
                    if !own && size <= self.chain_cut * peak {
                        open = false;
                        break;
                    }
                }
                if open && prev != (0.0, 0.0) {
                    self.g_points.push(GPoint {
                        ix: nx,
                        iy,
                        g: (-prev.0, -prev.1),
                    });
                }
            }
            let start = self.g_start[i];
            let part = self.box_part(i, start);
            self.g_box.push(part);
        }
        self.g_start.push(self.g_points.len());
        self.d_start.push(self.d_points.len());
    }

    /// The block's corner (element indices) when the block lies entirely in the grid.
    fn full_corner(&self, j: usize) -> Option<(usize, usize)> {
        let a = &self.aggs[j];
        a.inside.then_some((a.bx * BLOCK, a.by * BLOCK))
    }

    /// Whether aggregate j covers its whole block (uniform traction e_x or e_y there).
    fn full_adhesion(&self, j: usize) -> bool {
        let a = &self.aggs[j];
        a.kind != Kind::Slip && a.count == BLOCK * BLOCK && a.inside
    }

    /// Whether aggregate j covers its whole block (its traction change is replaced by its
    /// mean there in the near entries: exact in adhesion, a model in slip).
    fn full_block(&self, j: usize) -> bool {
        let a = &self.aggs[j];
        (a.kind != Kind::Slip || self.slip_mean) && a.count == BLOCK * BLOCK && a.inside
    }

    /// The box part of g_i (points from `start` on): when the aggregate covers its whole block
    /// and g_i is the same there (to 1e-9), those points are removed and their common value
    /// returned.
    fn box_part(&mut self, i: usize, start: usize) -> Option<(f64, f64)> {
        if !self.full_adhesion(i) {
            return None;
        }
        let (x0, _) = self.full_corner(i)?;
        let inside = |p: &GPoint| p.ix >= x0 && p.ix < x0 + BLOCK;
        let pts = &self.g_points[start..];
        let first = pts.iter().find(|p| inside(p))?.g;
        let tol = 1e-9 * (first.0.abs() + first.1.abs());
        let same = |p: &GPoint| (p.g.0 - first.0).abs() + (p.g.1 - first.1).abs() <= tol;
        let count = pts.iter().filter(|p| inside(p)).count();
        if count != BLOCK * BLOCK || !pts.iter().filter(|p| inside(p)).all(same) {
            return None;
        }
        let mut w = start;
        for r in start..self.g_points.len() {
            if !inside(&self.g_points[r]) {
                self.g_points[w] = self.g_points[r];
                w += 1;
            }
        }
        self.g_points.truncate(w);
        Some(first)
    }

    /// g_i summed over the cells of the far-field grid.
    fn far_weights(&mut self) {
        self.gc_start.clear();
        self.gc.clear();
        for i in 0..self.aggs.len() {
            self.gc_start.push(self.gc.len());
            if let Some(g) = self.g_box[i] {
                let c = self.aggs[i].by * self.ncx + self.aggs[i].bx;
                let nb = (BLOCK * BLOCK) as f64;
                self.cell_acc[c] = (nb * g.0, nb * g.1);
                self.touched.push(c);
            }
            for p in &self.g_points[self.g_start[i]..self.g_start[i + 1]] {
                let c = (p.iy / BLOCK) * self.ncx + p.ix / BLOCK;
                let a = &mut self.cell_acc[c];
                if *a == (0.0, 0.0) {
                    self.touched.push(c);
                }
                a.0 += p.g.0;
                a.1 += p.g.1;
            }
            for &c in &self.touched {
                let a = std::mem::take(&mut self.cell_acc[c]);
                self.gc.push(Cell {
                    index: c as u32,
                    at: ((c % self.ncx) as u32, (c / self.ncx) as u32),
                    g: a,
                });
            }
            self.touched.clear();
        }
        self.gc_start.push(self.gc.len());
    }

    /// out = M r (module documentation); `sys` is the system E was built for.
    pub(super) fn apply(&mut self, sys: &NewtonSystem, r: &[f64], out: &mut [f64]) {
        sys.precondition(r, &mut self.z);
        if !self.ready {
            out.copy_from_slice(&self.z);
            return;
        }
        self.rhs.fill(0.0);
        for (s, &a) in self.slot_agg.iter().enumerate() {
            if a != NONE {
                self.rhs[a as usize] += self.z[s];
            }
        }
        let mut rhs = std::mem::take(&mut self.rhs);
        let mut y = std::mem::take(&mut self.y);
        let mut work = std::mem::take(&mut self.work);
        gmres_with(&mut Coarse(self), &rhs, &mut y, INNER_TOL, INNER, &mut work);
        self.work = work;
        for (s, &a) in self.slot_agg.iter().enumerate() {
            out[s] = if a == NONE {
                self.z[s]
            } else {
                let agg = &self.aggs[a as usize];
                self.z[s] - rhs[a as usize] / agg.count as f64 + y[a as usize]
            };
        }
        rhs.fill(0.0);
        self.rhs = rhs;
        self.y = y;
    }

    /// out = E y: the sparse part plus the far field by the convolution on the block grid.
    fn coarse_product(&mut self, y: &[f64], out: &mut [f64]) {
        self.fx.fill(0.0);
        self.fy.fill(0.0);
        for (a, &v) in self.aggs.iter().zip(y) {
            let c = a.by * self.ncx + a.bx;
            self.fx[c] += a.force.0 * v;
            self.fy[c] += a.force.1 * v;
        }
        let [sxx, sxy, syy] = &self.spectra;
        self.conv.apply_block(
            [sxx, sxy, syy],
            (&self.fx, &self.fy),
            (&mut self.ux, &mut self.uy),
        );
        for (i, o) in out.iter_mut().enumerate() {
            let mut s = 0.0;
            let r = self.e_start[i]..self.e_start[i + 1];
            for (&j, &v) in self.e_col[r.clone()].iter().zip(&self.e_corr[r]) {
                s += v * y[j as usize];
            }
            for &Cell { index, g, .. } in &self.gc[self.gc_start[i]..self.gc_start[i + 1]] {
                s += g.0 * self.ux[index as usize] + g.1 * self.uy[index as usize];
            }
            *o = s;
        }
    }

    /// out = one forward Gauss–Seidel sweep from zero on the near part of E: the solve with
    /// its lower triangle.
    fn sweep(&self, r: &[f64], out: &mut [f64]) {
        for i in 0..out.len() {
            let mut s = r[i];
            for &(j, v) in &self.lo[self.lo_start[i]..self.lo_start[i + 1]] {
                s -= v * out[j as usize];
            }
            out[i] = s / self.e_diag[i];
        }
    }

    /// The dense coarse matrix as the inner solve sees it (tests).
    #[cfg(test)]
    pub(super) fn coarse_matrix(&mut self, exact_only: bool) -> Vec<f64> {
        let m = self.aggs.len();
        let mut out = vec![0.0; m * m];
        if exact_only {
            for i in 0..m {
                for e in self.e_start[i]..self.e_start[i + 1] {
                    out[i * m + self.e_col[e] as usize] = self.e_val[e];
                }
            }
        } else {
            let (mut y, mut col) = (vec![0.0; m], vec![0.0; m]);
            for j in 0..m {
                y.fill(0.0);
                y[j] = 1.0;
                self.coarse_product(&y, &mut col);
                for i in 0..m {
                    out[i * m + j] = col[i];
                }
            }
        }
        out
    }

    /// Whether coarse unknowns i and j lie in blocks at most [`NEAR`] apart (tests).
    #[cfg(test)]
    pub(super) fn near(&self, i: usize, j: usize) -> bool {
        self.block_distance(i, j) <= NEAR
    }

    /// Pᵀ v (tests).
    #[cfg(test)]
    pub(super) fn restrict(&self, v: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; self.aggs.len()];
        for (s, &a) in self.slot_agg.iter().enumerate() {
            if a != NONE {
                out[a as usize] += v[s];
            }
        }
        out
    }

    /// P y (tests).
    #[cfg(test)]
    pub(super) fn prolong(&self, y: &[f64]) -> Vec<f64> {
        self.slot_agg
            .iter()
            .map(|&a| if a == NONE { 0.0 } else { y[a as usize] })
            .collect()
    }
}

/// The coarse system E y = Pᵀ z for the inner GMRES.
struct Coarse<'a>(&'a mut TwoLevel);

impl LinearProblem for Coarse<'_> {
    fn apply(&mut self, x: &[f64], out: &mut [f64]) {
        self.0.coarse_product(x, out);
    }

    fn precondition(&mut self, r: &[f64], out: &mut [f64]) {
        self.0.sweep(r, out);
    }
}

#[cfg(test)]
mod tests;
