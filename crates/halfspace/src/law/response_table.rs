//! A response table F(δ) of the boundary-element law on its base gap, shared by identical
//! contacts (issue #14; references.md §C8.4, "Response table").
//!
//! Without column corrections (a wheel on a flat, rigid, smooth track) the undeformed gap of
//! a [`BemLaw`](super::BemLaw) is its base gap h₀ minus the approach δ only, so its force is a
//! function F(δ) of one variable, the same for every law with the same grid, material and
//! base gap. The table holds exact solves (NormCG to [`NODE_TOL`]) at nodes δ_0 < δ_1 < … and
//! answers between two nodes by the chord
//!
//! ```text
//! F(δ) ≈ F_i + s_i (δ − δ_i),   s_i = (F_{i+1} − F_i)/(δ_{i+1} − δ_i),
//! ```
//!
//! with the same linear interpolation of the pressure field and the column forces, the chord
//! slope as dF/dδ and the chord's integral for the energy.
//!
//! **Error bound.** On a fixed contact set C the discrete pressure is p_C = A_CC⁻¹(δ 1 − h_C),
//! linear in δ, so the discrete F(δ) is piecewise linear, and convex while the set grows with δ
//! (dF/dδ = ΔA 1ᵀA_CC⁻¹1 grows with C for a positive definite A). For a convex F the chord lies
//! above F, and F lies above the two lines through the interval's ends with the slopes of the
//! neighbouring chords, s_{i−1} (a lower bound of F' at δ_i) and s_{i+1} (an upper bound of F'
//! at δ_{i+1}). The gap between the chord and the larger of the two lines is largest where the
//! lines cross:
//!
//! ```text
//! |F(δ) − chord(δ)| ≤ e_i = a b h/(a + b),   a = s_i − s_{i−1},  b = s_{i+1} − s_i,  h = δ_{i+1} − δ_i.
//! ```
//!
//! The table bisects every interval whose relative bound e_i / F_i exceeds the tolerance
//! (`reuse_tol`) until all pass or [`MAX_NODES`] is reached; an interval whose neighbouring
//! chords are not convex beyond round-off, or that still fails, is not used (the law solves).
//! The table covers forces from [`MIN_FORCE_FRACTION`] to [`MAX_FORCE_FACTOR`] times the
//! grid's design force; outside it the law solves as before.

use std::sync::OnceLock;

use crate::error::ContactError;
use crate::grid::Grid;
use crate::material::Material;
use crate::normcg::{NormalLoad, NormalSolver, SolverOptions};

/// NormCG tolerance of the table's node solves (‖Δp‖_rms/‖p‖_rms), far below any useful
/// `reuse_tol`.
pub const NODE_TOL: f64 = 1e-9;
/// The table covers forces from this fraction of the design force up (below it the law
/// solves: near first contact the relative bound of a chord cannot be met).
pub const MIN_FORCE_FRACTION: f64 = 0.05;
/// The table covers forces up to this multiple of the design force (the patch of the wheel's
/// grid, 1.25 × the Hertz semi-axes at the design force, fills the grid at about 1.95 ×; a
/// wheel bouncing after a slope kink exceeds the design force).
pub const MAX_FORCE_FACTOR: f64 = 2.0;
/// Largest number of nodes of one table.
pub const MAX_NODES: usize = 4096;
/// An interval is split no closer to its ends than this fraction of its width.
const SPLIT_MARGIN: f64 = 0.05;
/// Step ratio of the a-priori nodes (1 + this) in t = δ − min h₀.
const INITIAL_STEP: f64 = 0.04;
/// Splitting passes over the failing intervals.
const MAX_PASSES: usize = 30;

/// One node of the table: an exact solve at δ.
#[derive(Debug, Clone, Copy)]
struct Node {
    delta: f64,
    force: f64,
    energy: f64,
    max_pressure: f64,
    patch: (f64, f64),
}

/// The answer of the table at one approach.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TableAnswer {
    /// F \[N\] (the chord).
    pub force: f64,
    /// dF/dδ \[N/m\] (the chord's slope).
    pub stiffness: f64,
    /// W = ∫ F dδ \[J\] (the node's energy plus the chord's integral).
    pub energy: f64,
    /// Peak pressure \[Pa\] (interpolated).
    pub max_pressure: f64,
    /// Patch length and width \[m\] (interpolated).
    pub patch: (f64, f64),
    /// Bound of the force error relative to the interval's lower node force (module
    /// documentation).
    pub estimate: f64,
}

/// The response table of one base gap (module documentation).
#[derive(Debug)]
pub struct ResponseTable {
    nodes: Vec<Node>,
    /// Column forces \[N\], `nx` per node.
    column_force: Vec<f64>,
    /// Pressure \[Pa\], `n` per node.
    pressure: Vec<f64>,
    /// Per interval (nodes i, i + 1): the relative bound e_i/F_i, infinite where not used.
    estimate: Vec<f64>,
    nx: usize,
    n: usize,
    solves: usize,
    tol: f64,
}

/// A solve at one approach with its fields.
struct Solved {
    node: Node,
    column_force: Vec<f64>,
    pressure: Vec<f64>,
}

fn solve_node(
    solver: &mut NormalSolver,
    base_gap: &[f64],
    delta: f64,
    options: &SolverOptions,
) -> Result<Solved, ContactError> {
    let s = solver.solve(base_gap, NormalLoad::Approach(delta), options)?;
    let grid = *solver.grid();
    let (nx, area) = (grid.nx, grid.element_area());
    let mut column_force = vec![0.0; nx];
    for (k, p) in s.pressure.iter().enumerate() {
        column_force[k % nx] += p * area;
    }
    let work: f64 = s
        .pressure
        .iter()
        .zip(&s.displacement)
        .map(|(p, u)| p * u)
        .sum();
    let patch = if s.elements_in_contact > 0 {
        let (a, b) = s.patch_half_widths();
        (2.0 * a, 2.0 * b)
    } else {
        (0.0, 0.0)
    };
    Ok(Solved {
        node: Node {
            delta,
            force: s.normal_force,
            energy: 0.5 * area * work,
            max_pressure: s.max_pressure,
            patch,
        },
        column_force,
        pressure: s.pressure,
    })
}

/// The relative bound of interval i of the chords `slope` (module documentation): a b h/(a+b)
/// over the lower node force, infinite at the ends, below `min_force` or where the chords are
/// not convex beyond round-off.
fn interval_bound(nodes: &[Node], slope: &[f64], i: usize, min_force: f64) -> f64 {
    if i == 0 || i + 2 >= nodes.len() || nodes[i].force < min_force {
        return f64::INFINITY;
    }
    let (sl, s, sr) = (slope[i - 1], slope[i], slope[i + 1]);
    // Round-off of a chord slope: the nodes' force errors over the interval widths.
    let noise = 8.0 * NODE_TOL * nodes[i + 1].force
        / (nodes[i + 1].delta - nodes[i].delta).min(nodes[i].delta - nodes[i - 1].delta);
    let (a, b) = (s - sl, sr - s);
    if a < -noise || b < -noise {
        return f64::INFINITY;
    }
    let (a, b) = (a.max(0.0) + noise, b.max(0.0) + noise);
    let h = nodes[i + 1].delta - nodes[i].delta;
    (a * b * h / (a + b)) / nodes[i].force + 4.0 * NODE_TOL
}

impl ResponseTable {
    /// Builds the table of the base gap `base_gap` on `grid` for forces up to `max_force`
    /// \[N\] with the relative tolerance `tol` (> 0).
    pub fn build(
        grid: Grid,
        material: Material,
        base_gap: &[f64],
        max_force: f64,
        tol: f64,
    ) -> Result<Self, ContactError> {
        crate::error::positive("max_force", max_force)?;
        crate::error::positive("reuse_tol", tol)?;
        let mut solver = NormalSolver::new(grid, material)?;
        let options = SolverOptions {
            tol: NODE_TOL,
            max_iter: 5000,
            sensitivity: false,
            ..SolverOptions::default()
        };
        let h_min = base_gap.iter().copied().fold(f64::INFINITY, f64::min);
        let min_force = MIN_FORCE_FRACTION * max_force;
        let d_hi = solver
            .solve(
                base_gap,
                NormalLoad::Force(MAX_FORCE_FACTOR * max_force),
                &options,
            )?
            .approach;
        let d_lo = solver
            .solve(base_gap, NormalLoad::Force(min_force), &options)?
            .approach;
        // A priori nodes, geometric in t = δ − h_min (about one set change per interval at
        // 32 × 32); the splits then find the set changes.
        let mut deltas = vec![h_min];
        let (mut t, t_hi) = (d_lo - h_min, d_hi - h_min);
        let ratio = 1.0 + INITIAL_STEP;
        // One node below the range: the left neighbour chord of the first interval used.
        deltas.push(h_min + t / ratio);
        while t < t_hi {
            deltas.push(h_min + t);
            t *= ratio;
        }
        deltas.push(h_min + t_hi);
        deltas.push(h_min + t_hi * ratio);
        let mut solved = Vec::with_capacity(deltas.len());
        for &d in &deltas {
            solved.push(solve_node(&mut solver, base_gap, d, &options)?);
        }
        let mut solves = solved.len() + 2;
        let mut estimate = Vec::new();
        for _ in 0..MAX_PASSES {
            estimate = Self::bounds(&solved, min_force);
            let failing: Vec<usize> = (0..estimate.len())
                .filter(|&i| {
                    estimate[i] > tol && solved[i].node.force >= min_force && i + 2 < solved.len()
                })
                .collect();
            if failing.is_empty() || solved.len() + failing.len() > MAX_NODES {
                break;
            }
            let mut start = vec![0.0; grid.len()];
            for &i in &failing {
                let d = Self::split_point(&solved, i);
                // Start from the chord's pressure (exact when the interval holds no set
                // change).
                let (lo, hi) = (&solved[i], &solved[i + 1]);
                let th = (d - lo.node.delta) / (hi.node.delta - lo.node.delta);
                for ((s, a), b) in start.iter_mut().zip(&lo.pressure).zip(&hi.pressure) {
                    *s = a + th * (b - a);
                }
                solver.set_initial_pressure(&start)?;
                let node = solve_node(&mut solver, base_gap, d, &options)?;
                solved.push(node);
                solves += 1;
            }
            solved.sort_by(|a, b| a.node.delta.total_cmp(&b.node.delta));
        }
        if estimate.len() + 1 != solved.len() {
            estimate = Self::bounds(&solved, min_force);
        }
        let (nx, n) = (grid.nx, grid.len());
        let mut table = ResponseTable {
            nodes: Vec::with_capacity(solved.len()),
            column_force: Vec::with_capacity(solved.len() * nx),
            pressure: Vec::with_capacity(solved.len() * n),
            estimate,
            nx,
            n,
            solves,
            tol,
        };
        for s in solved {
            table.nodes.push(s.node);
            table.column_force.extend_from_slice(&s.column_force);
            table.pressure.extend_from_slice(&s.pressure);
        }
        Ok(table)
    }

    /// Where interval i is split: where the lines through its ends with the neighbouring
    /// chords' slopes cross (the largest gap of the bound, and the kink itself when the
    /// interval holds one kink between two linear pieces: then both halves are exact),
    /// kept within the middle 90 % of the interval.
    fn split_point(solved: &[Solved], i: usize) -> f64 {
        let n = |j: usize| solved[j].node;
        let slope = |j: usize| (n(j + 1).force - n(j).force) / (n(j + 1).delta - n(j).delta);
        let (sl, s, sr) = (slope(i - 1), slope(i), slope(i + 1));
        let (a, b) = ((s - sl).max(0.0), (sr - s).max(0.0));
        let frac = if a + b > 0.0 { b / (a + b) } else { 0.5 };
        let frac = frac.clamp(SPLIT_MARGIN, 1.0 - SPLIT_MARGIN);
        n(i).delta + frac * (n(i + 1).delta - n(i).delta)
    }

    fn bounds(solved: &[Solved], min_force: f64) -> Vec<f64> {
        let nodes: Vec<Node> = solved.iter().map(|s| s.node).collect();
        let slope: Vec<f64> = nodes
            .windows(2)
            .map(|w| (w[1].force - w[0].force) / (w[1].delta - w[0].delta))
            .collect();
        (0..slope.len())
            .map(|i| interval_bound(&nodes, &slope, i, min_force))
            .collect()
    }

    /// Exact solves the table was built from.
    pub fn solves(&self) -> usize {
        self.solves
    }

    /// Nodes of the table.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the table has no node (never after [`ResponseTable::build`]).
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The tolerance the table was refined to.
    pub fn tol(&self) -> f64 {
        self.tol
    }

    /// The range of approaches \[m\] the table answers in part (the first and last node).
    pub fn range(&self) -> (f64, f64) {
        (self.nodes[0].delta, self.nodes[self.nodes.len() - 1].delta)
    }

    /// The answer at `delta` \[m\] with the column forces (`nx` values) and the pressure
    /// (`n` values) written, or `None` when δ lies in an interval the table does not use.
    pub fn answer(
        &self,
        delta: f64,
        column_force: &mut [f64],
        pressure: &mut [f64],
    ) -> Option<TableAnswer> {
        let i = self
            .nodes
            .partition_point(|n| n.delta <= delta)
            .checked_sub(1)?;
        let estimate = *self.estimate.get(i)?;
        if estimate.is_nan() || estimate > self.tol {
            return None;
        }
        let (lo, hi) = (&self.nodes[i], &self.nodes[i + 1]);
        let h = hi.delta - lo.delta;
        let t = delta - lo.delta;
        let th = t / h;
        let slope = (hi.force - lo.force) / h;
        let lerp = |a: f64, b: f64| a + th * (b - a);
        let (nx, n) = (self.nx, self.n);
        let (c0, c1) = (
            &self.column_force[i * nx..(i + 1) * nx],
            &self.column_force[(i + 1) * nx..(i + 2) * nx],
        );
        for ((c, a), b) in column_force.iter_mut().zip(c0).zip(c1) {
            *c = lerp(*a, *b);
        }
        let (p0, p1) = (
            &self.pressure[i * n..(i + 1) * n],
            &self.pressure[(i + 1) * n..(i + 2) * n],
        );
        for ((p, a), b) in pressure.iter_mut().zip(p0).zip(p1) {
            *p = lerp(*a, *b);
        }
        Some(TableAnswer {
            force: lo.force + slope * t,
            stiffness: slope,
            energy: lo.energy + t * (lo.force + 0.5 * slope * t),
            max_pressure: lerp(lo.max_pressure, hi.max_pressure),
            patch: (lerp(lo.patch.0, hi.patch.0), lerp(lo.patch.1, hi.patch.1)),
            estimate,
        })
    }
}

/// A response table shared by identical laws, built on the first evaluation that can use it
/// (so a run that never meets a flat, rigid, smooth track never pays for it).
#[derive(Debug)]
pub struct SharedTable {
    max_force: f64,
    tol: f64,
    cell: OnceLock<Option<ResponseTable>>,
}

impl SharedTable {
    /// A table for forces up to `max_force` \[N\] refined to the relative tolerance `tol`; the
    /// laws sharing it must have the same grid, material and base gap.
    pub fn new(max_force: f64, tol: f64) -> Self {
        Self {
            max_force,
            tol,
            cell: OnceLock::new(),
        }
    }

    /// The table, built now if it is not yet (`None` if its solves failed: the laws then
    /// solve every evaluation).
    pub fn get(&self, grid: Grid, material: Material, base_gap: &[f64]) -> Option<&ResponseTable> {
        self.cell
            .get_or_init(|| {
                ResponseTable::build(grid, material, base_gap, self.max_force, self.tol).ok()
            })
            .as_ref()
    }

    /// The table if it has been built.
    pub fn built(&self) -> Option<&ResponseTable> {
        self.cell.get().and_then(Option::as_ref)
    }
}
