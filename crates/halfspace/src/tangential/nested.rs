//! Nested iteration (the start of a full-multigrid cycle) for steady rolling: a cold solve
//! first solves the same case on the grid with elements twice as large (recursively, down to
//! about 20 × 20 elements) and starts the fine Newton–Krylov solve from the prolonged coarse
//! tractions and adhesion/slip split (module documentation of [`super`], "Nested start";
//! references.md §C3.12).
//!
//! The continuum problem does not depend on the grid (the same pressure field, creepages,
//! spin and friction), so the coarse solution differs from the fine one by the discretisation
//! error, O(h), mostly at the edge of the slip zone. Coarse pressure: the mean of the 2 × 2
//! fine pressures of each coarse element (missing children of an odd grid count as zero),
//! the L² projection onto piecewise constants. Prolongation: the coarse traction is copied to
//! its four children; children of a coarse slip element slip in the coarse traction's
//! direction on their own bound, the others keep the coarse traction, put on their own bound
//! when it exceeds it (they slip then).

use super::{Creepages, RollingLoad, TangentialOptions, TangentialSolver};
use crate::grid::Grid;
use crate::operator::{FftTangentialInfluence, TangentialInfluenceOperator};

/// Smallest number of elements per direction of a coarse grid: a grid is coarsened when
/// both nx and ny are at least twice this.
pub(super) const MIN_COARSE: usize = 20;

/// Relative tolerance of the coarse solves: their algebraic error only has to lie below the
/// coarse discretisation error (measured: tighter coarse tolerances do not reduce the fine
/// products, "Performance" in docs/tangential.md).
const COARSE_TOL: f64 = 1e-4;

/// The coarse level of a nested start: its solver (its own coarse level inside, recursively)
/// and the restricted pressure.
#[derive(Debug)]
pub(super) struct CoarseLevel {
    solver: Box<TangentialSolver<FftTangentialInfluence>>,
    pressure: Vec<f64>,
}

/// The grid with elements twice as large over the same lower-left corner (⌈nx/2⌉ × ⌈ny/2⌉
/// elements), or `None` when `g` is too small to coarsen.
pub(super) fn coarse_grid(g: &Grid) -> Option<Grid> {
    if g.nx < 2 * MIN_COARSE || g.ny < 2 * MIN_COARSE {
        return None;
    }
    Grid::new(
        g.nx.div_ceil(2),
        g.ny.div_ceil(2),
        2.0 * g.dx,
        2.0 * g.dy,
        g.x0,
        g.y0,
    )
    .ok()
}

/// Index of the coarse parent of fine element (ix, iy).
fn parent(coarse: &Grid, ix: usize, iy: usize) -> usize {
    (iy / 2) * coarse.nx + ix / 2
}

/// Operator products of the coarse levels of one nested start, per level (level 1 the
/// first coarser grid) with their element counts, for cost accounting.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CoarseProducts {
    /// (elements of the level's grid, operator products on it), finest coarse level first.
    pub levels: Vec<(usize, usize)>,
}

impl CoarseProducts {
    /// Add the products of another nested start level by level.
    pub(super) fn add(&mut self, other: &CoarseProducts) {
        for (i, &(m, p)) in other.levels.iter().enumerate() {
            match self.levels.get_mut(i) {
                Some(level) => level.1 += p,
                None => self.levels.push((m, p)),
            }
        }
    }

    /// Products on all coarse levels together.
    pub fn total(&self) -> usize {
        self.levels.iter().map(|l| l.1).sum()
    }

    /// Σ products × (N_level log N_level)/(N log N): the coarse work in units of products
    /// on the fine grid of `n` elements (an FFT product costs O(N log N)).
    pub fn fine_equivalent(&self, n: usize) -> f64 {
        let cost = |m: usize| {
            let m = m.max(2) as f64;
            m * m.ln()
        };
        self.levels
            .iter()
            .map(|&(m, p)| p as f64 * cost(m) / cost(n))
            .sum()
    }
}

impl<T: TangentialInfluenceOperator> TangentialSolver<T> {
    /// Set the tractions to the prolonged solution of the same steady-rolling case
    /// (creepages `c`, friction `self.mu`) on the coarse grid; `None` (tractions untouched)
    /// when the grid is too small, a bound is not finite (Newton's full-adhesion probes) or
    /// the coarse solve fails. Returns the coarse levels' products.
    pub(super) fn nested_start(
        &mut self,
        c: Creepages,
        options: &TangentialOptions,
    ) -> Option<CoarseProducts> {
        let g = *self.grid();
        let cg = coarse_grid(&g)?;
        if self.bound.iter().any(|b| !b.is_finite()) || self.mu <= 0.0 {
            return None;
        }
        if self.coarse.is_none() {
            let op = FftTangentialInfluence::new(cg, self.operator.material()).ok()?;
            let solver = TangentialSolver::with_operator(op).ok()?;
            self.coarse = Some(CoarseLevel {
                solver: Box::new(solver),
                pressure: vec![0.0; cg.len()],
            });
        }
        let level = self.coarse.as_mut()?;
        level.pressure.fill(0.0);
        for iy in 0..g.ny {
            for ix in 0..g.nx {
                level.pressure[parent(&cg, ix, iy)] += 0.25 * self.pn[iy * g.nx + ix];
            }
        }
        let coarse_options = TangentialOptions {
            tol: options.tol.max(COARSE_TOL),
            ..*options
        };
        level.solver.reset();
        let s = level
            .solver
            .steady_rolling(
                &level.pressure,
                self.mu,
                RollingLoad::Creepages(c),
                &coarse_options,
            )
            .ok()?;
        let mut products = CoarseProducts {
            levels: vec![(cg.len(), s.products)],
        };
        products
            .levels
            .extend_from_slice(&level.solver.coarse_products.levels);
        let coarse = &level.solver;
        for iy in 0..g.ny {
            for ix in 0..g.nx {
                let k = iy * g.nx + ix;
                let kc = parent(&cg, ix, iy);
                let bound = self.bound[k];
                let (qx, qy) = (coarse.px[kc], coarse.py[kc]);
                let q = qx.hypot(qy);
                (self.px[k], self.py[k]) = if bound <= 0.0 {
                    (0.0, 0.0)
                } else if q > 0.0 && (coarse.slipping[kc] || q >= bound) {
                    (bound * qx / q, bound * qy / q)
                } else {
                    (qx, qy)
                };
            }
        }
        Some(products)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gap::GapShape;
    use crate::material::Material;
    use crate::normcg::{NormalLoad, NormalSolver, SolverOptions};
    use crate::operator::TangentialKernel;
    use crate::tangential::coupling::Coupling;

    #[test]
    fn coarse_grids_halve_and_cover_the_fine_grid() {
        let g = Grid::new(45, 40, 1e-4, 2e-4, -1e-3, 2e-3).unwrap();
        let c = coarse_grid(&g).unwrap();
        assert_eq!((c.nx, c.ny), (23, 20));
        assert_eq!((c.dx, c.dy, c.x0, c.y0), (2e-4, 4e-4, -1e-3, 2e-3));
        // Every fine element lies inside its parent.
        for iy in 0..g.ny {
            for ix in 0..g.nx {
                let k = parent(&c, ix, iy);
                let (x, y) = g.centre(iy * g.nx + ix);
                let (xc, yc) = c.centre(k);
                assert!((x - xc).abs() < 0.5 * c.dx && (y - yc).abs() < 0.5 * c.dy);
            }
        }
        assert!(coarse_grid(&Grid::new(39, 100, 1e-4, 1e-4, 0.0, 0.0).unwrap()).is_none());
        assert!(coarse_grid(&Grid::new(100, 1, 1e-4, 1e-4, 0.0, 0.0).unwrap()).is_none());
    }

    #[test]
    fn fine_equivalent_weights_levels_by_fft_cost() {
        let mut p = CoarseProducts {
            levels: vec![(100, 10)],
        };
        p.add(&CoarseProducts {
            levels: vec![(100, 5), (25, 8)],
        });
        assert_eq!(p.levels, vec![(100, 15), (25, 8)]);
        assert_eq!(p.total(), 23);
        let w = |m: f64| m * m.ln();
        let expected = 15.0 + 8.0 * w(25.0) / w(100.0);
        assert!((p.fine_equivalent(100) - expected).abs() < 1e-12);
    }

    /// The coarse case has the fine case's load (the restricted pressure keeps the normal
    /// force), and the prolonged start keeps the coarse tractions where they are within the
    /// fine bound and puts the children of coarse slip elements on their own bound, in the
    /// coarse traction's direction.
    #[test]
    fn restriction_keeps_the_load_and_prolongation_the_split() {
        let m = Material::from_combined(82e9, 0.28).unwrap();
        let shape = GapShape::Quadratic {
            a: 0.8,
            b: 0.281417,
        };
        let h = shape.hertz(&m, NormalLoad::Force(106.7e3)).unwrap();
        let n = 41;
        let g = Grid::centred(n, n, 2.1 * h.a / n as f64, 2.1 * h.b / n as f64, 0.0, 0.0).unwrap();
        let gap = shape.sample(&g).unwrap();
        let normal = NormalSolver::new(g, m)
            .unwrap()
            .solve(&gap, NormalLoad::Force(106.7e3), &SolverOptions::default())
            .unwrap();
        let mut s = TangentialSolver::new(g, m).unwrap();
        s.set_bound(&normal.pressure, 0.3).unwrap();
        s.operator.prepare(TangentialKernel::Steady);
        s.prepare_coupling(Coupling::Steady);
        let c = Creepages {
            xi: 1e-3,
            eta: 2e-4,
            phi: 0.0,
        };
        s.set_rigid(g.dx, c, (0.0, 0.0));
        let products = s.nested_start(c, &TangentialOptions::default()).unwrap();
        assert_eq!(products.levels.len(), 1);
        assert!(products.levels[0].1 > 0);
        let level = s.coarse.as_ref().unwrap();
        let cg = *level.solver.grid();
        let fine: f64 = normal.pressure.iter().sum::<f64>() * g.element_area();
        let coarse: f64 = level.pressure.iter().sum::<f64>() * cg.element_area();
        assert!((fine - coarse).abs() <= 1e-12 * fine);
        let (mut slip, mut adhesion) = (0, 0);
        for iy in 0..g.ny {
            for ix in 0..g.nx {
                let k = iy * g.nx + ix;
                let kc = parent(&cg, ix, iy);
                let (qx, qy) = (level.solver.px[kc], level.solver.py[kc]);
                let (px, py) = (s.px[k], s.py[k]);
                let bound = s.bound[k];
                let t = px.hypot(py);
                assert!(t <= bound * (1.0 + 1e-12), "element {k}");
                if bound <= 0.0 {
                    continue;
                }
                if level.solver.slipping[kc] || qx.hypot(qy) >= bound {
                    slip += 1;
                    assert!((t - bound).abs() <= 1e-12 * bound, "element {k}");
                    assert!((px * qy - py * qx).abs() <= 1e-9 * t * qx.hypot(qy));
                    assert!(px * qx + py * qy > 0.0);
                } else {
                    adhesion += 1;
                    assert_eq!((px, py), (qx, qy), "element {k}");
                }
            }
        }
        assert!(slip > 100 && adhesion > 100, "{slip} {adhesion}");
    }
}
