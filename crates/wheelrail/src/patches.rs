//! The elastic contact of one wheel: its candidates grouped into patches, each solved by the
//! half-space solver on a grid in its contact plane, all under one vertical approach of the
//! wheel (references.md §W3).
//!
//! Candidates whose separation is within reach of the vertical approach take part. Two
//! candidates are solved together, on one grid in the plane of the closer one, when their
//! contact angles differ by less than [`PatchOptions::merge_angle`] and their potential
//! contact areas overlap or nearly touch across the track (they then interact elastically);
//! otherwise each gets its own grid and its own solve (far apart, the elastic interaction is
//! neglected). Moving the wheel down by δ_v reduces the normal distance in a plane of contact
//! angle γ by δ_v cos γ; a patch's normal force F_n has the vertical component F_n cos γ and
//! the lateral one −F_n sin γ (towards the track centre for a flange contact).

use halfspace::{Grid, Material, NormalLoad, NormalSolution, NormalSolver, SolverOptions};

use crate::contact_point::ContactCandidate;
use crate::error::{WheelRailError, in_range};
use crate::gap::{ContactPlane, Side};
use crate::wheelset::{Wheelset, WheelsetContact};

/// The load on one wheel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum WheelLoad {
    /// Vertical force on the wheel \[N\].
    VerticalForce(f64),
    /// Vertical approach of the wheel from its rigid touching position \[m\].
    VerticalApproach(f64),
}

/// Grid and iteration settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchOptions {
    /// Elements along the track per patch.
    pub nx: usize,
    /// Elements across the track per patch.
    pub ny: usize,
    /// Potential contact area relative to the rigid overlap at the estimated approach.
    pub margin: f64,
    /// Largest contact-angle difference of candidates solved on one grid \[rad\].
    pub merge_angle: f64,
    /// Relative tolerance on the vertical force (prescribed force).
    pub force_tol: f64,
}

impl Default for PatchOptions {
    fn default() -> Self {
        PatchOptions {
            nx: 48,
            ny: 48,
            margin: 1.3,
            merge_angle: 10f64.to_radians(),
            force_tol: 1e-6,
        }
    }
}

impl PatchOptions {
    fn validate(&self) -> Result<(), WheelRailError> {
        in_range("nx", self.nx as f64, 4.0, 1024.0, "must lie in [4, 1024]")?;
        in_range("ny", self.ny as f64, 4.0, 1024.0, "must lie in [4, 1024]")?;
        in_range("margin", self.margin, 1.0, 4.0, "must lie in [1, 4]")?;
        in_range(
            "merge_angle",
            self.merge_angle,
            0.0,
            0.5,
            "must lie in [0, 0.5] rad",
        )?;
        in_range(
            "force_tol",
            self.force_tol,
            1e-12,
            1e-2,
            "must lie in [1e-12, 1e-2]",
        )?;
        Ok(())
    }
}

/// One solved contact patch.
#[derive(Debug, Clone)]
pub struct Patch {
    /// Indices of the wheel's candidates solved on this patch's grid.
    pub candidates: Vec<usize>,
    /// Contact angle of the patch's plane \[rad\].
    pub contact_angle: f64,
    /// The plane's origin in the side's track frame (Y, Z) \[m\].
    pub origin: (f64, f64),
    /// Centre of pressure in the side's track frame (Y, Z) \[m\] (x = along the track).
    pub centre: (f64, f64, f64),
    /// The half-space solution on the patch's grid (x along the track, y = t across it).
    pub solution: NormalSolution,
    /// Normal force \[N\].
    pub normal_force: f64,
    /// Vertical component \[N\].
    pub vertical_force: f64,
    /// Lateral component \[N\] (positive towards the field side of this wheel).
    pub lateral_force: f64,
}

/// The elastic contact of one wheel.
#[derive(Debug, Clone)]
pub struct WheelSolution {
    /// Which wheel.
    pub side: Side,
    /// Vertical approach from the rigid touching position \[m\].
    pub vertical_approach: f64,
    /// Patches in contact.
    pub patches: Vec<Patch>,
    /// Total vertical force \[N\].
    pub vertical_force: f64,
    /// Total lateral force \[N\].
    pub lateral_force: f64,
    /// Iterations of the vertical approach (prescribed force).
    pub iterations: usize,
}

/// A group of candidates on one grid.
struct Group<'a> {
    members: Vec<usize>,
    plane: ContactPlane<'a>,
    solver: NormalSolver,
    gap: Vec<f64>,
}

/// Plane extent across the track where the rigid overlap h(0, t) < depth, around `t0`
/// (stepping out in 2 µm steps to the first t where it exceeds `depth`, at most 0.1 m).
///
/// The walk goes in strides of [`STRIDE`] steps, checking the stride's end, and repeats the
/// stride step by step where it ends outside: the same first exceedance as the plain 2 µm
/// walk (unless h(0, t) exceeds `depth` and falls back within one stride of 50 µm, far below
/// a patch's width), with about 1/[`STRIDE`] of the profile evaluations.
fn extent(plane: &ContactPlane<'_>, t0: f64, depth: f64) -> (f64, f64) {
    const STEP: f64 = 2e-6;
    const STEPS: usize = 50_000;
    let inside = |t: f64| matches!(plane.cross_gap(t), Some(h) if h < depth);
    let walk = |dir: f64| -> f64 {
        let at = |k: usize| t0 + dir * STEP * k as f64;
        let mut k = 0;
        while k < STEPS {
            let end = (k + STRIDE).min(STEPS);
            if inside(at(end)) {
                k = end;
                continue;
            }
            for j in k + 1..=end {
                if !inside(at(j)) {
                    return at(j);
                }
            }
            k = end;
        }
        at(STEPS)
    };
    (walk(-1.0), walk(1.0))
}

/// Steps of 2 µm checked at once by [`extent`].
const STRIDE: usize = 25;

fn sample(plane: &ContactPlane<'_>, grid: &Grid) -> Vec<f64> {
    let mut out = vec![f64::INFINITY; grid.len()];
    for iy in 0..grid.ny {
        let t = grid.y(iy);
        let (Some(h0), Some(r)) = (plane.cross_gap(t), plane.rolling_radius(t)) else {
            continue;
        };
        let c = (plane.angle - plane.roll).cos();
        for ix in 0..grid.nx {
            let x = grid.x(ix);
            if x.abs() < r {
                out[iy * grid.nx + ix] = h0 + (r - (r * r - x * x).sqrt()) * c;
            }
        }
    }
    out
}

/// Hertz estimate of the vertical approach of one candidate under vertical force `fv`,
/// from its curvatures (used to size the grids; the conformal case is capped).
fn hertz_estimate(
    c: &ContactCandidate,
    radius: f64,
    roll: f64,
    material: &Material,
    fv: f64,
) -> f64 {
    let g = c.contact_angle();
    let a = (g - roll).cos() / (2.0 * radius);
    let b = (0.5 * (c.wheel_curvature - c.rail_curvature)).max(0.25);
    let fn_ = fv / g.cos().max(0.2);
    match halfspace::Hertz::elliptic(a, b, material.e_star, fn_) {
        Ok(h) => h.approach / g.cos().max(0.2),
        Err(_) => 1e-4,
    }
}

/// Solve the elastic contact of the `side` wheel of the rigid contact `contact`.
pub fn solve_wheel(
    wheelset: &Wheelset,
    contact: &WheelsetContact,
    side: Side,
    material: &Material,
    load: WheelLoad,
    options: &PatchOptions,
) -> Result<WheelSolution, WheelRailError> {
    options.validate()?;
    let wheel = match side {
        Side::Right => &contact.right,
        Side::Left => &contact.left,
    };
    let roll = match side {
        Side::Right => contact.roll,
        Side::Left => -contact.roll,
    };
    let principal = wheel.principal();
    // The approach that sizes the grids.
    let (sizing, target) = match load {
        WheelLoad::VerticalForce(f) => {
            in_range("vertical_force", f, 1.0, 1e7, "must lie in [1, 1e7] N")?;
            (
                hertz_estimate(principal, wheel.rolling_radius(), roll, material, f),
                Some(f),
            )
        }
        WheelLoad::VerticalApproach(d) => {
            in_range("approach", d, 1e-9, 5e-3, "must lie in [1e-9, 5e-3] m")?;
            (d, None)
        }
    };
    let mut scale = options.margin;
    for _attempt in 0..6 {
        let reach = sizing * scale;
        let mut groups = build_groups(wheelset, contact, side, wheel, reach, material, options)?;
        let (approach, iterations, solutions) = match target {
            None => (sizing, 0, solve_all(&mut groups, sizing)?),
            Some(f) => solve_for_force(&mut groups, sizing, f, options)?,
        };
        let at_edge = solutions
            .iter()
            .any(|s| touches_edge(s) && s.normal_force > 0.0);
        if at_edge {
            scale *= 1.5;
            continue;
        }
        return Ok(assemble(side, groups, solutions, approach, iterations));
    }
    Err(WheelRailError::NotConverged {
        what: "patch grid covering the contact (it kept reaching the grid's edge)",
        iterations: 6,
        residual: scale,
    })
}

fn touches_edge(s: &NormalSolution) -> bool {
    let g = &s.grid;
    (0..g.nx).any(|ix| s.in_contact[ix] || s.in_contact[(g.ny - 1) * g.nx + ix])
        || (0..g.ny).any(|iy| s.in_contact[iy * g.nx] || s.in_contact[iy * g.nx + g.nx - 1])
}

fn build_groups<'a>(
    wheelset: &'a Wheelset,
    contact: &WheelsetContact,
    side: Side,
    wheel: &crate::wheelset::WheelContact,
    reach: f64,
    material: &Material,
    options: &PatchOptions,
) -> Result<Vec<Group<'a>>, WheelRailError> {
    // Candidates within reach, in order across the track.
    let mut idx: Vec<usize> = (0..wheel.candidates.len())
        .filter(|&i| wheel.candidates[i].gap < reach)
        .collect();
    idx.sort_by(|&a, &b| wheel.candidates[a].y.total_cmp(&wheel.candidates[b].y));
    // Each candidate's lateral extent in its own plane, mapped to track Y.
    let spans: Vec<(f64, f64)> = idx
        .iter()
        .map(|&i| {
            let c = &wheel.candidates[i];
            let plane = ContactPlane::new(wheelset, contact, side, c);
            let (lo, hi) = extent(&plane, 0.0, reach * c.contact_angle().cos());
            (plane.to_track(lo, 0.0).0, plane.to_track(hi, 0.0).0)
        })
        .collect();
    let mut clusters: Vec<Vec<usize>> = Vec::new();
    for (k, &i) in idx.iter().enumerate() {
        if let Some(last) = clusters.last_mut() {
            let j = *last.last().expect("non-empty");
            let kj = idx.iter().position(|&q| q == j).expect("member");
            let (a, b) = (&wheel.candidates[j], &wheel.candidates[i]);
            let width = (spans[kj].1 - spans[kj].0) + (spans[k].1 - spans[k].0);
            let close = spans[k].0 - spans[kj].1 < 0.5 * width;
            if close && (a.contact_angle() - b.contact_angle()).abs() < options.merge_angle {
                last.push(i);
                continue;
            }
        }
        clusters.push(vec![i]);
    }
    let mut groups = Vec::new();
    for members in clusters {
        // The plane of the closest member.
        let lead = *members
            .iter()
            .min_by(|&&a, &&b| wheel.candidates[a].gap.total_cmp(&wheel.candidates[b].gap))
            .expect("non-empty");
        let c = &wheel.candidates[lead];
        let plane = ContactPlane::new(wheelset, contact, side, c);
        let depth = reach * c.contact_angle().cos();
        // Lateral extent covering every member's overlap.
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for &m in &members {
            let cm = &wheel.candidates[m];
            // The member's position in the lead plane.
            let (s, co) = plane.angle.sin_cos();
            let t0 = (cm.y - plane.origin.0) * co + (cm.z - plane.origin.1) * s;
            let (a, b) = extent(&plane, t0, depth);
            lo = lo.min(a);
            hi = hi.max(b);
        }
        let r = plane.rolling_radius(0.0).unwrap_or(0.46);
        let xmax = (2.0 * r * depth / (plane.angle - plane.roll).cos().max(0.1)).sqrt();
        let grid = Grid::new(
            options.nx,
            options.ny,
            2.0 * xmax / options.nx as f64,
            (hi - lo) / options.ny as f64,
            -xmax,
            lo,
        )
        .map_err(|source| WheelRailError::Contact {
            patch: groups.len(),
            source,
        })?;
        let gap = sample(&plane, &grid);
        let solver =
            NormalSolver::new(grid, *material).map_err(|source| WheelRailError::Contact {
                patch: groups.len(),
                source,
            })?;
        groups.push(Group {
            members,
            plane,
            solver,
            gap,
        });
    }
    Ok(groups)
}

fn solver_options() -> SolverOptions {
    SolverOptions {
        sensitivity: true,
        ..SolverOptions::default()
    }
}

/// Solve every group at vertical approach `dv`.
fn solve_all(groups: &mut [Group<'_>], dv: f64) -> Result<Vec<NormalSolution>, WheelRailError> {
    let opts = solver_options();
    groups
        .iter_mut()
        .enumerate()
        .map(|(k, g)| {
            let dn = dv * g.plane.angle.cos();
            g.solver
                .solve(&g.gap, NormalLoad::Approach(dn), &opts)
                .map_err(|source| WheelRailError::Contact { patch: k, source })
        })
        .collect()
}

fn vertical(groups: &[Group<'_>], sols: &[NormalSolution]) -> (f64, f64) {
    let fv: f64 = groups
        .iter()
        .zip(sols)
        .map(|(g, s)| s.normal_force * g.plane.angle.cos())
        .sum();
    let dfv: f64 = groups
        .iter()
        .zip(sols)
        .map(|(g, s)| s.dfn_dapproach.unwrap_or(0.0) * g.plane.angle.cos().powi(2))
        .sum();
    (fv, dfv)
}

/// Newton on the vertical approach with dF_v/dδ_v = Σ dF_n/dδ_n cos²γ (the solver's
/// sensitivities), safeguarded by a bracket and the power law F ∝ δ^{3/2}.
fn solve_for_force(
    groups: &mut [Group<'_>],
    start: f64,
    target: f64,
    options: &PatchOptions,
) -> Result<(f64, usize, Vec<NormalSolution>), WheelRailError> {
    let (mut lo, mut hi) = (0.0, f64::INFINITY);
    let mut dv = start;
    let mut last = f64::NAN;
    for it in 1..=60 {
        let sols = solve_all(groups, dv)?;
        let (fv, dfv) = vertical(groups, &sols);
        last = fv / target - 1.0;
        if last.abs() < options.force_tol {
            return Ok((dv, it, sols));
        }
        if fv < target {
            lo = dv;
        } else {
            hi = dv;
        }
        let mut next = if fv > 0.0 && dfv > 0.0 {
            dv + (target - fv) / dfv
        } else if fv > 0.0 {
            dv * (target / fv).powf(2.0 / 3.0)
        } else {
            2.0 * dv
        };
        if !(next > lo && next < hi) {
            next = if hi.is_finite() {
                0.5 * (lo + hi)
            } else {
                2.0 * dv
            };
        }
        dv = next;
    }
    Err(WheelRailError::NotConverged {
        what: "vertical approach for the prescribed wheel force",
        iterations: 60,
        residual: last,
    })
}

fn assemble(
    side: Side,
    groups: Vec<Group<'_>>,
    solutions: Vec<NormalSolution>,
    approach: f64,
    iterations: usize,
) -> WheelSolution {
    let mut patches = Vec::new();
    for (g, s) in groups.into_iter().zip(solutions) {
        if s.normal_force <= 0.0 {
            continue;
        }
        let (xc, tc) = s.centre_of_pressure;
        let (yc, zc) = g.plane.to_track(tc, 0.0);
        let (sin, cos) = g.plane.angle.sin_cos();
        patches.push(Patch {
            candidates: g.members,
            contact_angle: g.plane.angle,
            origin: g.plane.origin,
            centre: (xc, yc, zc),
            normal_force: s.normal_force,
            vertical_force: s.normal_force * cos,
            lateral_force: -s.normal_force * sin,
            solution: s,
        });
    }
    WheelSolution {
        side,
        vertical_approach: approach,
        vertical_force: patches.iter().map(|p| p.vertical_force).sum(),
        lateral_force: patches.iter().map(|p| p.lateral_force).sum(),
        patches,
        iterations,
    }
}
