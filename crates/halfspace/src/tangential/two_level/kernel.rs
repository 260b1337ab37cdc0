//! Tables of the direct kernel A for the coarse matrix of the two-level preconditioner:
//! A itself at every element offset (one column beyond the grid included), A summed over a
//! block of sources (the field of a uniform traction on a block) and summed over two blocks
//! (a block's total response to a uniform traction on another block, at block offsets).
//!
//! With B = the BLOCK × BLOCK offsets s = (0 … b − 1)², the tables hold
//!
//! ```text
//! A(o),   Σ_s A(o − s),   Σ_s Σ_s' A(b Δ + s − s')
//! ```
//!
//! the last at block offsets Δ. A is even, A(−o) = A(o) (xx and yy are even in each
//! coordinate, xy odd in each), which gives the response of a block's sources at an element
//! from the same box table. The box sums run as sliding sums along x, then along y: O(N) per
//! table, no product.

use super::BLOCK;
use crate::operator::TangentialInfluenceOperator;

/// The three tables (module documentation), components (xx, xy, yy).
pub(super) struct KernelTables {
    nx: isize,
    ny: isize,
    /// Row length of the element-offset tables: o_x ∈ [−nx, nx].
    w: usize,
    /// A and Σ_s A(o − s), the components of each offset together.
    a: Vec<[f64; 3]>,
    boxed: Vec<[f64; 3]>,
    /// Blocks per row and column of the grid (block-offset table 2nbx − 1 wide).
    nbx: isize,
    nby: isize,
    blocks: [Vec<f64>; 3],
}

impl KernelTables {
    /// Read A from `op` (its table where it has one) and sum it over blocks.
    pub(super) fn new<T: TangentialInfluenceOperator>(op: &T) -> Self {
        let g = op.grid();
        let (nx, ny) = (g.nx as isize, g.ny as isize);
        let (w, h) = ((2 * nx + 1) as usize, (2 * ny - 1) as usize);
        let mut a = [vec![0.0; w * h], vec![0.0; w * h], vec![0.0; w * h]];
        for j in 0..h {
            for i in 0..w {
                let (xx, xy, yy) = op.direct_coefficient((i as isize - nx, j as isize - ny + 1));
                a[0][j * w + i] = xx;
                a[1][j * w + i] = xy;
                a[2][j * w + i] = yy;
            }
        }
        let b = BLOCK;
        // Σ_s A(o − s): entries whose sum would leave the table stay zero (never read).
        let boxed_parts = a.clone().map(|t| {
            let mut sx = vec![0.0; w * h];
            for j in 0..h {
                let row = &t[j * w..(j + 1) * w];
                let mut run: f64 = row[..b.min(w)].iter().sum();
                for i in b - 1..w {
                    if i >= b {
                        run += row[i] - row[i - b];
                    }
                    sx[j * w + i] = run;
                }
            }
            let mut out = vec![0.0; w * h];
            for i in 0..w {
                let mut run: f64 = (0..b.min(h)).map(|j| sx[j * w + i]).sum();
                for j in b - 1..h {
                    if j >= b {
                        run += sx[j * w + i] - sx[(j - b) * w + i];
                    }
                    out[j * w + i] = run;
                }
            }
            out
        });
        let interleave = |t: &[Vec<f64>; 3]| -> Vec<[f64; 3]> {
            (0..w * h).map(|i| [t[0][i], t[1][i], t[2][i]]).collect()
        };
        let (a, boxed) = (interleave(&a), interleave(&boxed_parts));
        let (nbx, nby) = (g.nx.div_ceil(b) as isize, g.ny.div_ceil(b) as isize);
        let (bw, bh) = ((2 * nbx - 1) as usize, (2 * nby - 1) as usize);
        let mut tables = KernelTables {
            nx,
            ny,
            w,
            a,
            boxed,
            nbx,
            nby,
            blocks: [vec![0.0; bw * bh], vec![0.0; bw * bh], vec![0.0; bw * bh]],
        };
        // Σ_s Σ_s' A(bΔ + s − s') = Σ_s boxed(bΔ + s), for the offsets the table holds.
        let bi = b as isize;
        for j in 0..bh {
            let dy = (j as isize - nby + 1) * bi;
            for i in 0..bw {
                let dx = (i as isize - nbx + 1) * bi;
                let mut sum = (0.0, 0.0, 0.0);
                for sy in 0..bi {
                    for sx in 0..bi {
                        let o = (dx + sx, dy + sy);
                        if tables.holds(o) {
                            let v = tables.boxed(o);
                            sum = (sum.0 + v.0, sum.1 + v.1, sum.2 + v.2);
                        }
                    }
                }
                tables.blocks[0][j * bw + i] = sum.0;
                tables.blocks[1][j * bw + i] = sum.1;
                tables.blocks[2][j * bw + i] = sum.2;
            }
        }
        tables
    }

    fn holds(&self, (ox, oy): (isize, isize)) -> bool {
        ox.abs() <= self.nx && oy.abs() < self.ny
    }

    fn index(&self, (ox, oy): (isize, isize)) -> usize {
        debug_assert!(
            self.holds((ox, oy)),
            "offset ({ox}, {oy}) outside the table"
        );
        (oy + self.ny - 1) as usize * self.w + (ox + self.nx) as usize
    }

    /// A(o).
    #[inline]
    pub(super) fn a(&self, o: (isize, isize)) -> (f64, f64, f64) {
        let [xx, xy, yy] = self.a[self.index(o)];
        (xx, xy, yy)
    }

    /// Σ_s A(o − s): the field at offset o from a block's corner of a unit traction on the
    /// whole block (o − s within the table for every s).
    #[inline]
    pub(super) fn boxed(&self, o: (isize, isize)) -> (f64, f64, f64) {
        let [xx, xy, yy] = self.boxed[self.index(o)];
        (xx, xy, yy)
    }

    /// Σ_s Σ_s' A(bΔ + s − s') at the block offset Δ.
    #[inline]
    pub(super) fn blocks(&self, (dx, dy): (isize, isize)) -> (f64, f64, f64) {
        let i = (dy + self.nby - 1) as usize * (2 * self.nbx - 1) as usize
            + (dx + self.nbx - 1) as usize;
        (self.blocks[0][i], self.blocks[1][i], self.blocks[2][i])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::Grid;
    use crate::material::Material;
    use crate::operator::DirectTangentialInfluence;

    /// The box tables equal the plain sums of the closed-form coefficients (to round-off),
    /// at offsets between elements and blocks that lie inside an 11 × 9 grid.
    #[test]
    fn box_sums_equal_plain_sums() {
        let m = Material::from_combined(82e9, 0.28).unwrap();
        let grid = Grid::centred(11, 9, 0.5e-3, 0.7e-3, 0.0, 0.0).unwrap();
        let op = DirectTangentialInfluence::new(grid, m).unwrap();
        let t = KernelTables::new(&op);
        let b = BLOCK as isize;
        let close = |u: (f64, f64, f64), v: (f64, f64, f64)| {
            let s = u.0.abs() + u.2.abs();
            (u.0 - v.0).abs() + (u.1 - v.1).abs() + (u.2 - v.2).abs() <= 1e-12 * s
        };
        for (ox, oy) in [(0, 0), (3, 2), (-7, 5), (11, -5), (-5, 8), (6, -5)] {
            let mut s = (0.0, 0.0, 0.0);
            for sy in 0..b {
                for sx in 0..b {
                    let v = op.direct_coefficient((ox - sx, oy - sy));
                    s = (s.0 + v.0, s.1 + v.1, s.2 + v.2);
                }
            }
            assert!(close(t.boxed((ox, oy)), s), "({ox}, {oy})");
        }
        for (dx, dy) in [(0, 0), (1, 0), (-1, 1), (1, -1)] {
            let mut s = (0.0, 0.0, 0.0);
            let quad = |k: isize| (k % b, k / b % b, k / b / b % b, k / b / b / b);
            for (sx, sy, px, py) in (0..b * b * b * b).map(quad) {
                let v = op.direct_coefficient((dx * b + sx - px, dy * b + sy - py));
                s = (s.0 + v.0, s.1 + v.1, s.2 + v.2);
            }
            assert!(close(t.blocks((dx, dy)), s), "block ({dx}, {dy})");
        }
    }
}
