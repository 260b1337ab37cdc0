//! The rows of the coarse matrix E (module documentation of [`super`]): exact entries
//! between near blocks by formula (iv) from the kernel tables, the D entries along each ψ_i,
//! the point model of the near pairs (subtracted: the far-field convolution adds it back for
//! every pair) and the lower part that the Gauss–Seidel sweep reads.

use super::{BLOCK, Cell, GPoint, Kind, NEAR, NONE, SWEEP_NEAR, TwoLevel};

impl TwoLevel {
    /// The far-field kernel between the cell (cx, cy) (observation) and the block of
    /// aggregate j (source).
    pub(super) fn far_kernel(&self, (cx, cy): (u32, u32), j: usize) -> (f64, f64, f64) {
        let (cx, cy) = (cx as isize, cy as isize);
        let (bx, by) = (self.aggs[j].bx as isize, self.aggs[j].by as isize);
        let wx = 2 * self.ncx - 1;
        let i = ((cy - by + self.nby as isize - 1) as usize) * wx
            + (cx - bx + self.ncx as isize - 1) as usize;
        (self.far_xx[i], self.far_xy[i], self.far_yy[i])
    }

    /// The rows of E: exact entries between near blocks, D entries along each ψ_i, and the
    /// point model of the near pairs subtracted (it is added back by the convolution).
    pub(super) fn rows(&mut self) {
        let m = self.aggs.len();
        self.row_pos.clear();
        self.row_pos.resize(m, NONE);
        self.e_start.clear();
        self.e_col.clear();
        self.e_val.clear();
        self.e_corr.clear();
        self.e_diag.clear();
        let g_points = std::mem::take(&mut self.g_points);
        for i in 0..m {
            let start = self.e_col.len();
            self.e_start.push(start);
            let (bx, by) = (self.aggs[i].bx, self.aggs[i].by);
            let gp = &g_points[self.g_start[i]..self.g_start[i + 1]];
            for nby_ in by.saturating_sub(NEAR)..(by + NEAR + 1).min(self.nby) {
                for nbx_ in bx.saturating_sub(NEAR)..(bx + NEAR + 1).min(self.nbx) {
                    for j in self.block_aggs[nby_ * self.nbx + nbx_] {
                        if j != NONE {
                            let value = self.near_entry(i, j as usize, gp);
                            let model = self.near_model(i, j as usize);
                            self.add_entry(j, value, model);
                        }
                    }
                }
            }
            // D entries along ψ_i (through the slip elements upstream of the block).
            for d in self.d_start[i]..self.d_start[i + 1] {
                let (j, v) = self.d_points[d];
                self.add_entry(j, v, 0.0);
            }
            let mut diag = 0.0;
            for e in start..self.e_col.len() {
                let j = self.e_col[e];
                if j as usize == i {
                    diag = self.e_val[e];
                }
                self.row_pos[j as usize] = NONE;
            }
            self.e_diag.push(diag);
        }
        self.e_start.push(self.e_col.len());
        self.g_points = g_points;
        self.lower_part();
    }

    /// The strictly lower part of the near entries (the forward Gauss–Seidel sweep from zero
    /// reads no other), between blocks at most [`SWEEP_NEAR`] apart.
    pub(super) fn lower_part(&mut self) {
        self.lo_start.clear();
        self.lo.clear();
        for i in 0..self.aggs.len() {
            self.lo_start.push(self.lo.len());
            for e in self.e_start[i]..self.e_start[i + 1] {
                let j = self.e_col[e] as usize;
                if j < i && self.block_distance(i, j) <= SWEEP_NEAR {
                    self.lo.push((j as u32, self.e_val[e]));
                }
            }
        }
        self.lo_start.push(self.lo.len());
    }

    /// Chebyshev distance between the blocks of aggregates i and j.
    pub(super) fn block_distance(&self, i: usize, j: usize) -> usize {
        let (a, b) = (&self.aggs[i], &self.aggs[j]);
        a.bx.abs_diff(b.bx).max(a.by.abs_diff(b.by))
    }

    /// Σ_p g_i(p)·(A f_j)(p) (module documentation) from the kernel tables: block sums
    /// where g_i or f_j is uniform on a whole block, element sums elsewhere.
    pub(super) fn near_entry(&self, i: usize, j: usize, gp: &[GPoint]) -> f64 {
        let t = &self.tables;
        let dot = |g: (f64, f64), (xx, xy, yy): (f64, f64, f64), f: (f64, f64)| {
            g.0 * (xx * f.0 + xy * f.1) + g.1 * (xy * f.0 + yy * f.1)
        };
        let unit = match self.aggs[j].kind {
            Kind::AdhesionX => (1.0, 0.0),
            Kind::AdhesionY => (0.0, 1.0),
            Kind::Slip => {
                let (f, nb) = (self.aggs[j].force, (BLOCK * BLOCK) as f64);
                (f.0 / nb, f.1 / nb)
            }
        };
        let corner = |a: usize| self.full_corner(a).map(|(x, y)| (x as isize, y as isize));
        // f_j uniform on its whole block: block sums; else its elements.
        let box_j = if self.full_block(j) { corner(j) } else { None };
        let sources = &self.f_points[self.f_start[j]..self.f_start[j + 1]];
        let mut s = 0.0;
        if let Some(g) = self.g_box[i] {
            let ci = corner(i).expect("box part of a full block");
            match box_j {
                Some(cj) => {
                    let b = BLOCK as isize;
                    s += dot(g, t.blocks(((ci.0 - cj.0) / b, (ci.1 - cj.1) / b)), unit);
                }
                None => {
                    for &(qx, qy, f) in sources {
                        s += dot(g, t.boxed((qx - ci.0, qy - ci.1)), f);
                    }
                }
            }
        }
        for p in gp {
            let (px, py) = (p.ix as isize, p.iy as isize);
            match box_j {
                Some(cj) => s += dot(p.g, t.boxed((px - cj.0, py - cj.1)), unit),
                None => {
                    for &(qx, qy, f) in sources {
                        s += dot(p.g, t.a((px - qx, py - qy)), f);
                    }
                }
            }
        }
        s
    }

    /// Add `value` (exact) and `value − model` to entry (current row, j).
    pub(super) fn add_entry(&mut self, j: u32, value: f64, model: f64) {
        let pos = self.row_pos[j as usize];
        if pos == NONE {
            self.row_pos[j as usize] = self.e_col.len() as u32;
            self.e_col.push(j);
            self.e_val.push(value);
            self.e_corr.push(value - model);
        } else {
            self.e_val[pos as usize] += value;
            self.e_corr[pos as usize] += value - model;
        }
    }

    /// The point model of E_ij: Σ_c G_i(c)·A(c − B_j) F_j.
    pub(super) fn near_model(&self, i: usize, j: usize) -> f64 {
        let force = self.aggs[j].force;
        let mut s = 0.0;
        for &Cell {
            at, g: (gx, gy), ..
        } in &self.gc[self.gc_start[i]..self.gc_start[i + 1]]
        {
            let (axx, axy, ayy) = self.far_kernel(at, j);
            s += gx * (axx * force.0 + axy * force.1) + gy * (axy * force.0 + ayy * force.1);
        }
        s
    }
}
