//! `dyncontact contact CASE.toml`: the quasi-static normal contact problem from a case file.
//!
//! Every key is in SI units; unknown keys are errors. See the README for the schema, and
//! docs/tangential.md for the \[friction\] and \[kinematics\] sections (tangential contact).

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, anyhow, bail};
use halfspace::{
    Body, ContactError, CoupledOptions, CoupledProblem, Creepages, ElementState, FastsimInput,
    GapShape, Grid, Hertz, LineHertz, Material, NormalLoad, NormalSolution, NormalSolver,
    RollingLoad, ShiftLoad, SolverOptions, TangentialOptions, TangentialSolution, TangentialSolver,
    TangentialStrategy, auto_grid, curvatures_from_radii, fastsim, linear_forces, solve_coupled,
    tangential_strategy,
};
use serde::{Deserialize, Serialize};

use crate::output;
use crate::plot;

/// The case file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactCase {
    /// Optional; `run` dispatches on it.
    #[serde(default)]
    pub kind: Option<String>,
    pub body1: BodySpec,
    pub body2: BodySpec,
    pub gap: GapSpec,
    pub grid: Option<GridSpec>,
    pub load: LoadSpec,
    pub solver: Option<SolverSpec>,
    /// Coulomb friction (needed by \[kinematics\]).
    pub friction: Option<FrictionSpec>,
    /// Tangential problem: rolling or shift (see docs/tangential.md).
    pub kinematics: Option<KinematicsSpec>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrictionSpec {
    pub mu: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KinematicsSpec {
    /// "rolling" (steady rolling) or "shift" (Cattaneo–Mindlin).
    pub problem: Option<String>,
    pub creepage_x: Option<f64>,
    pub creepage_y: Option<f64>,
    /// Spin [1/m].
    pub spin: Option<f64>,
    /// Rigid shift \[m\] (shift problem).
    pub shift_x: Option<f64>,
    pub shift_y: Option<f64>,
    /// Prescribed tangential forces \[N\].
    pub force_x: Option<f64>,
    pub force_y: Option<f64>,
    /// "exact" (default), "fastsim" or "linear".
    pub method: Option<String>,
}

/// How the tangential problem is solved (the library's one method enum).
pub use halfspace::TangentialMethod;

/// The tangential problem of a case.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TangentialTask {
    Rolling(RollingLoad),
    Shift(ShiftLoad),
}

/// A validated \[friction\] + \[kinematics\] pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TangentialCase {
    pub mu: f64,
    pub task: TangentialTask,
    pub method: TangentialMethod,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    #[serde(rename = "E")]
    pub e: Option<f64>,
    pub nu: Option<f64>,
    #[serde(default)]
    pub rigid: bool,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GapSpec {
    pub kind: String,
    #[serde(rename = "A")]
    pub a: Option<f64>,
    #[serde(rename = "B")]
    pub b: Option<f64>,
    #[serde(rename = "R1x")]
    pub r1x: Option<f64>,
    #[serde(rename = "R1y")]
    pub r1y: Option<f64>,
    #[serde(rename = "R2x")]
    pub r2x: Option<f64>,
    #[serde(rename = "R2y")]
    pub r2y: Option<f64>,
    pub radius: Option<f64>,
    pub length: Option<f64>,
    pub edge_radius: Option<f64>,
    pub file: Option<PathBuf>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GridSpec {
    pub nx: Option<usize>,
    pub ny: Option<usize>,
    pub dx: Option<f64>,
    pub dy: Option<f64>,
    pub x0: Option<f64>,
    pub y0: Option<f64>,
    /// Elements per direction of the automatic grid (when nx, ny, dx, dy are absent).
    pub n: Option<usize>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadSpec {
    pub force: Option<f64>,
    pub approach: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSpec {
    pub tol: Option<f64>,
    pub max_iter: Option<usize>,
}

/// A case ready to solve.
pub struct PreparedCase {
    pub material: Material,
    pub shape: GapShape,
    pub grid: Grid,
    pub gap: Vec<f64>,
    pub load: NormalLoad,
    pub options: SolverOptions,
    /// Friction coefficient, when \[friction\] is given.
    pub mu: Option<f64>,
    /// The tangential problem, when \[kinematics\] is given.
    pub tangential: Option<TangentialCase>,
}

fn finite_key(section: &str, key: &str, value: Option<f64>) -> Result<Option<f64>> {
    match value {
        Some(v) if !v.is_finite() => bail!("[{section}] `{key}` = {v}: must be a finite number"),
        other => Ok(other),
    }
}

/// Validate \[friction\] and \[kinematics\].
fn tangential_case(
    friction: Option<&FrictionSpec>,
    kin: Option<&KinematicsSpec>,
) -> Result<(Option<f64>, Option<TangentialCase>)> {
    let mu = match friction {
        None => None,
        Some(f) => {
            let mu = f.mu.ok_or_else(|| {
                anyhow!("[friction]: missing `mu` (Coulomb friction coefficient)")
            })?;
            if !mu.is_finite() || mu <= 0.0 {
                bail!("[friction] `mu` = {mu}: must be a positive number");
            }
            Some(mu)
        }
    };
    let Some(k) = kin else {
        return Ok((mu, None));
    };
    let mu = mu.ok_or_else(|| anyhow!("[kinematics] needs a [friction] section with `mu`"))?;
    let cx = finite_key("kinematics", "creepage_x", k.creepage_x)?;
    let cy = finite_key("kinematics", "creepage_y", k.creepage_y)?;
    let spin = finite_key("kinematics", "spin", k.spin)?;
    let sx = finite_key("kinematics", "shift_x", k.shift_x)?;
    let sy = finite_key("kinematics", "shift_y", k.shift_y)?;
    let fx = finite_key("kinematics", "force_x", k.force_x)?;
    let fy = finite_key("kinematics", "force_y", k.force_y)?;
    let has_creep = cx.is_some() || cy.is_some();
    let has_shift = sx.is_some() || sy.is_some();
    let has_force = fx.is_some() || fy.is_some();
    let problem = match k.problem.as_deref() {
        Some("rolling") => "rolling",
        Some("shift") => "shift",
        Some(other) => {
            bail!("[kinematics] `problem` = \"{other}\": expected \"rolling\" or \"shift\"")
        }
        None if has_shift => "shift",
        None => "rolling",
    };
    let method = match k.method.as_deref() {
        None | Some("exact") => TangentialMethod::Exact,
        Some("fastsim") => TangentialMethod::Fastsim,
        Some("linear") => TangentialMethod::Linear,
        Some(other) => bail!(
            "[kinematics] `method` = \"{other}\": expected \"exact\", \"fastsim\" or \"linear\""
        ),
    };
    let task = if problem == "rolling" {
        for (key, set) in [("shift_x", sx.is_some()), ("shift_y", sy.is_some())] {
            if set {
                bail!("[kinematics] key `{key}` is not used by problem = \"rolling\"");
            }
        }
        match (has_creep, has_force) {
            (true, true) => bail!(
                "[kinematics]: give either the creepages `creepage_x`, `creepage_y` or the forces `force_x`, `force_y`, not both"
            ),
            (false, false) if spin.is_none() => bail!(
                "[kinematics]: missing `creepage_x`/`creepage_y`/`spin` or `force_x`/`force_y`"
            ),
            (false, true) => TangentialTask::Rolling(RollingLoad::Forces {
                fx: fx.unwrap_or(0.0),
                fy: fy.unwrap_or(0.0),
                phi: spin.unwrap_or(0.0),
            }),
            _ => TangentialTask::Rolling(RollingLoad::Creepages(Creepages {
                xi: cx.unwrap_or(0.0),
                eta: cy.unwrap_or(0.0),
                phi: spin.unwrap_or(0.0),
            })),
        }
    } else {
        for (key, set) in [
            ("creepage_x", cx.is_some()),
            ("creepage_y", cy.is_some()),
            ("spin", spin.is_some()),
        ] {
            if set {
                bail!("[kinematics] key `{key}` is not used by problem = \"shift\"");
            }
        }
        match (has_shift, has_force) {
            (true, true) => bail!(
                "[kinematics]: give either the shift `shift_x`, `shift_y` or the forces `force_x`, `force_y`, not both"
            ),
            (false, false) => {
                bail!("[kinematics]: missing `shift_x`/`shift_y` or `force_x`/`force_y`")
            }
            (true, false) => TangentialTask::Shift(ShiftLoad::Shift {
                wx: sx.unwrap_or(0.0),
                wy: sy.unwrap_or(0.0),
            }),
            (false, true) => TangentialTask::Shift(ShiftLoad::Forces {
                fx: fx.unwrap_or(0.0),
                fy: fy.unwrap_or(0.0),
            }),
        }
    };
    if method != TangentialMethod::Exact
        && !matches!(task, TangentialTask::Rolling(RollingLoad::Creepages(_)))
    {
        bail!(
            "[kinematics] `method` = \"{}\" needs problem = \"rolling\" with creepages (forces and shifts need method = \"exact\")",
            method.name()
        );
    }
    Ok((Some(mu), Some(TangentialCase { mu, task, method })))
}

/// Parse a case file's text (`base` resolves relative table paths).
pub fn parse(text: &str, base: &Path) -> Result<PreparedCase> {
    let case: ContactCase = toml::from_str(text).map_err(|e| anyhow!("invalid case file: {e}"))?;
    prepare(case, base)
}

fn body(spec: &BodySpec, section: &str) -> Result<Body> {
    if spec.rigid {
        if spec.e.is_some() || spec.nu.is_some() {
            bail!("[{section}]: a rigid body takes no `E` or `nu`");
        }
        return Ok(Body::Rigid);
    }
    let e = spec
        .e
        .ok_or_else(|| anyhow!("[{section}]: missing `E` (or set `rigid = true`)"))?;
    let nu = spec
        .nu
        .ok_or_else(|| anyhow!("[{section}]: missing `nu`"))?;
    Body::elastic(e, nu).map_err(|err| anyhow!("[{section}] {err}"))
}

fn material(case: &ContactCase) -> Result<Material> {
    let b1 = body(&case.body1, "body1")?;
    let b2 = body(&case.body2, "body2")?;
    Material::combine(b1, b2).map_err(|e| anyhow!("[body1]/[body2]: {e}"))
}

fn load(spec: &LoadSpec) -> Result<NormalLoad> {
    match (spec.force, spec.approach) {
        (Some(f), None) => {
            if !f.is_finite() || f <= 0.0 {
                bail!("[load] `force` = {f}: must be a positive number of newtons");
            }
            Ok(NormalLoad::Force(f))
        }
        (None, Some(d)) => {
            if !d.is_finite() {
                bail!("[load] `approach` = {d}: must be a finite number of metres");
            }
            Ok(NormalLoad::Approach(d))
        }
        (Some(_), Some(_)) => bail!("[load]: give exactly one of `force` or `approach`, not both"),
        (None, None) => bail!("[load]: missing load: give `force` [N] or `approach` [m]"),
    }
}

/// Reject keys of \[gap\] that its kind does not use.
fn only_keys(spec: &GapSpec, allowed: &[&str]) -> Result<()> {
    let present = [
        ("A", spec.a.is_some()),
        ("B", spec.b.is_some()),
        ("R1x", spec.r1x.is_some()),
        ("R1y", spec.r1y.is_some()),
        ("R2x", spec.r2x.is_some()),
        ("R2y", spec.r2y.is_some()),
        ("radius", spec.radius.is_some()),
        ("length", spec.length.is_some()),
        ("edge_radius", spec.edge_radius.is_some()),
        ("file", spec.file.is_some()),
    ];
    for (key, is_set) in present {
        if is_set && !allowed.contains(&key) {
            bail!("[gap] key `{key}` is not used by kind = \"{}\"", spec.kind);
        }
    }
    Ok(())
}

fn required(value: Option<f64>, key: &str) -> Result<f64> {
    value.ok_or_else(|| anyhow!("[gap]: missing `{key}`"))
}

fn shape(spec: &GapSpec, grid: Option<&Grid>, base: &Path) -> Result<GapShape> {
    let shape = match spec.kind.as_str() {
        "quadratic" => {
            only_keys(spec, &["A", "B", "R1x", "R1y", "R2x", "R2y"])?;
            let by_radii = [spec.r1x, spec.r1y, spec.r2x, spec.r2y]
                .iter()
                .any(Option::is_some);
            if by_radii && (spec.a.is_some() || spec.b.is_some()) {
                bail!(
                    "[gap]: give either `A`, `B` or the radii `R1x`, `R1y`, `R2x`, `R2y`, not both"
                );
            }
            if by_radii {
                let inf = f64::INFINITY;
                let (a, b) = curvatures_from_radii(
                    spec.r1x.unwrap_or(inf),
                    spec.r1y.unwrap_or(inf),
                    spec.r2x.unwrap_or(inf),
                    spec.r2y.unwrap_or(inf),
                )
                .map_err(|e| anyhow!("[gap] {e}"))?;
                GapShape::Quadratic { a, b }
            } else {
                GapShape::Quadratic {
                    a: required(spec.a, "A")?,
                    b: required(spec.b, "B")?,
                }
            }
        }
        "sphere" => {
            only_keys(spec, &["radius"])?;
            GapShape::Sphere {
                radius: required(spec.radius, "radius")?,
            }
        }
        "cylinder" => {
            only_keys(spec, &["radius", "length"])?;
            GapShape::Cylinder {
                radius: required(spec.radius, "radius")?,
                length: required(spec.length, "length")?,
            }
        }
        "punch" => {
            only_keys(spec, &["radius", "edge_radius"])?;
            GapShape::Punch {
                radius: required(spec.radius, "radius")?,
                edge_radius: required(spec.edge_radius, "edge_radius")?,
            }
        }
        "table" => {
            only_keys(spec, &["file"])?;
            let file = spec
                .file
                .as_ref()
                .ok_or_else(|| anyhow!("[gap]: missing `file`"))?;
            let grid = grid.ok_or_else(|| {
                anyhow!("[gap] kind = \"table\" needs a [grid] with nx, ny, dx, dy")
            })?;
            GapShape::Table {
                values: read_table(&base.join(file), grid)?,
            }
        }
        other => bail!(
            "[gap] `kind` = \"{other}\": expected \"quadratic\", \"sphere\", \"cylinder\", \"punch\" or \"table\""
        ),
    };
    shape.validate().map_err(|e| anyhow!("[gap] {e}"))?;
    Ok(shape)
}

/// A tabulated gap: a CSV of `ny` lines of `nx` values \[m\]; line k is row iy = k (lowest y
/// first). Lines starting with `#` are comments.
fn read_table(path: &Path, grid: &Grid) -> Result<Vec<f64>> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("[gap] cannot read `file` {}", path.display()))?;
    let mut values = Vec::with_capacity(grid.len());
    let mut rows = 0;
    for (lineno, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let row: Vec<f64> = line
            .split(',')
            .map(|v| v.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|e| anyhow!("[gap] {} line {}: {e}", path.display(), lineno + 1))?;
        if row.len() != grid.nx {
            bail!(
                "[gap] {} line {}: {} values, the grid has nx = {}",
                path.display(),
                lineno + 1,
                row.len(),
                grid.nx
            );
        }
        if let Some(v) = row.iter().find(|v| !v.is_finite()) {
            bail!(
                "[gap] {} line {}: value {v} is not finite",
                path.display(),
                lineno + 1
            );
        }
        values.extend(row);
        rows += 1;
    }
    if rows != grid.ny {
        bail!(
            "[gap] {}: {rows} rows, the grid has ny = {}",
            path.display(),
            grid.ny
        );
    }
    Ok(values)
}

fn explicit_grid(spec: &GridSpec) -> Result<Option<Grid>> {
    let all = [
        spec.nx.is_some(),
        spec.ny.is_some(),
        spec.dx.is_some(),
        spec.dy.is_some(),
    ];
    if all.iter().all(|s| !s) {
        if spec.x0.is_some() || spec.y0.is_some() {
            bail!("[grid]: `x0`/`y0` need `nx`, `ny`, `dx`, `dy`");
        }
        return Ok(None);
    }
    if spec.n.is_some() {
        bail!("[grid]: `n` sets the automatic grid; do not combine it with `nx`, `ny`, `dx`, `dy`");
    }
    let nx = spec.nx.ok_or_else(|| anyhow!("[grid]: missing `nx`"))?;
    let ny = spec.ny.ok_or_else(|| anyhow!("[grid]: missing `ny`"))?;
    let dx = spec.dx.ok_or_else(|| anyhow!("[grid]: missing `dx`"))?;
    let dy = spec.dy.ok_or_else(|| anyhow!("[grid]: missing `dy`"))?;
    let x0 = spec.x0.unwrap_or(-0.5 * nx as f64 * dx);
    let y0 = spec.y0.unwrap_or(-0.5 * ny as f64 * dy);
    Grid::new(nx, ny, dx, dy, x0, y0)
        .map(Some)
        .map_err(|e| anyhow!("[grid] {e}"))
}

fn prepare(case: ContactCase, base: &Path) -> Result<PreparedCase> {
    if let Some(kind) = &case.kind
        && kind != "contact"
    {
        bail!("`kind` = \"{kind}\" is not a contact case");
    }
    let material = material(&case)?;
    let load = load(&case.load)?;
    let grid_spec = case.grid.as_ref();
    let explicit = match grid_spec {
        Some(g) => explicit_grid(g)?,
        None => None,
    };
    let shape = shape(&case.gap, explicit.as_ref(), base)?;
    let grid = match explicit {
        Some(g) => g,
        None => {
            let n = grid_spec
                .and_then(|g| g.n)
                .unwrap_or(halfspace::AUTO_GRID_ELEMENTS);
            auto_grid(&shape, &material, load, n)
                .map_err(|e| anyhow!("[grid] automatic grid: {e}"))?
        }
    };
    let gap = shape.sample(&grid).map_err(|e| anyhow!("[gap] {e}"))?;
    let mut options = SolverOptions::default();
    if let Some(s) = &case.solver {
        if let Some(tol) = s.tol {
            if !tol.is_finite() || tol <= 0.0 || tol >= 1.0 {
                bail!("[solver] `tol` = {tol}: must lie in (0, 1)");
            }
            options.tol = tol;
        }
        if let Some(m) = s.max_iter {
            if m == 0 {
                bail!("[solver] `max_iter` = 0: must be at least 1");
            }
            options.max_iter = m;
        }
    }
    let (mu, tangential) = tangential_case(case.friction.as_ref(), case.kinematics.as_ref())?;
    if let Some(t) = &tangential
        && t.method != TangentialMethod::Exact
        && !matches!(shape, GapShape::Quadratic { .. } | GapShape::Sphere { .. })
    {
        bail!(
            "[kinematics] `method` = \"{}\" needs a Hertzian gap ([gap] kind = \"quadratic\" or \"sphere\")",
            t.method.name()
        );
    }
    Ok(PreparedCase {
        material,
        shape,
        grid,
        gap,
        load,
        options,
        mu,
        tangential,
    })
}

/// The JSON summary of a contact case.
#[derive(Debug, Serialize)]
pub struct ContactSummary {
    pub normal_force: f64,
    pub approach: f64,
    pub max_pressure: f64,
    pub contact_area: f64,
    pub elements_in_contact: usize,
    pub iterations: usize,
    pub residual: f64,
    pub converged: bool,
    pub dfn_dapproach: Option<f64>,
    pub solve_time_s: f64,
    pub centre_of_pressure: [f64; 2],
    pub grid: GridSummary,
    pub material: MaterialSummary,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hertz: Option<HertzSummary>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hertz_line: Option<LineHertzSummary>,
    /// Tangential results (top-level keys), when \[kinematics\] is given.
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub tangential: Option<TangentialSummary>,
}

/// Tangential results in the JSON summary (SI units; forces on body 1).
#[derive(Debug, Serialize)]
pub struct TangentialSummary {
    pub tangential_method: String,
    pub tangential_problem: String,
    pub mu: f64,
    pub tangential_force_x: f64,
    pub tangential_force_y: f64,
    /// M_z [N m] about the coordinate origin (null for the linear theory: C₃₃ is not tabulated).
    pub spin_moment: Option<f64>,
    pub adhesion_elements: Option<usize>,
    pub slip_elements: Option<usize>,
    /// Rolling: creepages used or found.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub creepage_x: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub creepage_y: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spin: Option<f64>,
    /// Shift: rigid shift used or found \[m\].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shift_x: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shift_y: Option<f64>,
    /// Rolling: frictional power per unit rolling speed \[N\] (× V gives W); shift: work \[J\].
    pub frictional_power: Option<f64>,
    pub tangential_iterations: Option<usize>,
    pub newton_iterations: Option<usize>,
    /// Normal–tangential outer iterations (K ≠ 0 with the exact method; absent otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub outer_iterations: Option<usize>,
    pub tangential_time_s: f64,
}

#[derive(Debug, Serialize)]
pub struct GridSummary {
    pub nx: usize,
    pub ny: usize,
    pub dx: f64,
    pub dy: f64,
    pub x0: f64,
    pub y0: f64,
}

#[derive(Debug, Serialize)]
pub struct MaterialSummary {
    #[serde(rename = "G")]
    pub g: f64,
    pub nu: f64,
    #[serde(rename = "K")]
    pub k: f64,
    pub e_star: f64,
}

#[derive(Debug, Serialize)]
pub struct HertzSummary {
    pub approach: f64,
    pub max_pressure: f64,
    pub a: f64,
    pub b: f64,
    pub normal_force: f64,
}

#[derive(Debug, Serialize)]
pub struct LineHertzSummary {
    pub a: f64,
    pub max_pressure: f64,
    pub force_per_length: f64,
}

/// Outcome of solving a case: the summary, and the solution (also when not converged).
pub struct CaseOutcome {
    pub summary: ContactSummary,
    pub solution: NormalSolution,
    /// The exact tangential solution, when \[kinematics\] with method = "exact" is given.
    pub tangential: Option<TangentialSolution>,
}

/// The Hertz ellipse (a, b) \[m\] of the case's quadratic gap at normal force `fn_`.
pub fn hertz_axes(case: &PreparedCase, fn_: f64) -> Result<(f64, f64)> {
    let h = case
        .shape
        .hertz(&case.material, NormalLoad::Force(fn_))
        .ok_or_else(|| anyhow!("[gap]: FASTSIM and the linear theory need a Hertzian gap"))?;
    Ok((h.a, h.b))
}

/// Solve the tangential problem of a case for the normal solution `normal`.
pub fn solve_tangential(
    case: &PreparedCase,
    t: &TangentialCase,
    normal: &NormalSolution,
) -> Result<(TangentialSummary, Option<TangentialSolution>)> {
    let start = Instant::now();
    let problem = match t.task {
        TangentialTask::Rolling(_) => "rolling",
        TangentialTask::Shift(_) => "shift",
    };
    let m = case.material;
    let mut summary = TangentialSummary {
        tangential_method: t.method.name().into(),
        tangential_problem: problem.into(),
        mu: t.mu,
        tangential_force_x: 0.0,
        tangential_force_y: 0.0,
        spin_moment: None,
        adhesion_elements: None,
        slip_elements: None,
        creepage_x: None,
        creepage_y: None,
        spin: None,
        shift_x: None,
        shift_y: None,
        frictional_power: None,
        tangential_iterations: None,
        newton_iterations: None,
        outer_iterations: None,
        tangential_time_s: 0.0,
    };
    let mut exact = None;
    match (t.method, t.task) {
        (TangentialMethod::Exact, task) => {
            let mut solver =
                TangentialSolver::new(case.grid, m).map_err(|e| anyhow!("tangential: {e}"))?;
            let opts = TangentialOptions::default();
            let sol = match task {
                TangentialTask::Rolling(load) => {
                    solver.steady_rolling(&normal.pressure, t.mu, load, &opts)
                }
                TangentialTask::Shift(load) => solver.shift(&normal.pressure, t.mu, load, &opts),
            }
            .map_err(|e| anyhow!("tangential problem: {e}"))?;
            summary.tangential_force_x = sol.force_x;
            summary.tangential_force_y = sol.force_y;
            summary.spin_moment = Some(sol.moment_z);
            summary.adhesion_elements = Some(sol.adhesion_elements);
            summary.slip_elements = Some(sol.slip_elements);
            if problem == "rolling" {
                summary.creepage_x = Some(sol.creepages.xi);
                summary.creepage_y = Some(sol.creepages.eta);
                summary.spin = Some(sol.creepages.phi);
            } else {
                summary.shift_x = Some(sol.shift.0);
                summary.shift_y = Some(sol.shift.1);
            }
            summary.frictional_power = Some(sol.frictional_power);
            summary.tangential_iterations = Some(sol.iterations);
            summary.newton_iterations = Some(sol.newton_iterations);
            exact = Some(sol);
        }
        (method, TangentialTask::Rolling(RollingLoad::Creepages(c))) => {
            let (a, b) = hertz_axes(case, normal.normal_force)?;
            summary.creepage_x = Some(c.xi);
            summary.creepage_y = Some(c.eta);
            summary.spin = Some(c.phi);
            if method == TangentialMethod::Fastsim {
                let f = fastsim_on(case, t.mu, normal.normal_force, a, b, c)?;
                summary.tangential_force_x = f.force_x;
                summary.tangential_force_y = f.force_y;
                summary.spin_moment = Some(f.moment_z);
                summary.adhesion_elements = Some(f.adhesion_elements);
                summary.slip_elements = Some(f.slip_elements);
                summary.frictional_power = Some(f.frictional_power_per_speed);
            } else {
                let (fx, fy) = linear_forces(m.g, m.nu, a, b, c.xi, c.eta, c.phi)
                    .map_err(|e| anyhow!("linear theory: {e}"))?;
                summary.tangential_force_x = fx;
                summary.tangential_force_y = fy;
            }
        }
        (method, _) => bail!(
            "[kinematics] `method` = \"{}\" needs creepages",
            method.name()
        ),
    }
    summary.tangential_time_s = start.elapsed().as_secs_f64();
    Ok((summary, exact))
}

/// The coupled normal–tangential solve of a case with K ≠ 0 (Panagiotopoulos' process).
fn solve_coupled_case(
    case: &PreparedCase,
    t: &TangentialCase,
) -> Result<(NormalSolution, TangentialSummary, TangentialSolution)> {
    let start = Instant::now();
    let mut normal = NormalSolver::new(case.grid, case.material).map_err(|e| anyhow!("{e}"))?;
    let mut tang = TangentialSolver::new(case.grid, case.material).map_err(|e| anyhow!("{e}"))?;
    let problem = match t.task {
        TangentialTask::Rolling(l) => CoupledProblem::SteadyRolling(l),
        TangentialTask::Shift(l) => CoupledProblem::Shift(l),
    };
    let c = solve_coupled(
        &mut normal,
        &mut tang,
        &case.gap,
        case.load,
        t.mu,
        problem,
        &case.options,
        &TangentialOptions::default(),
        &CoupledOptions::default(),
    )
    .map_err(|e| anyhow!("coupled normal-tangential problem (K != 0): {e}"))?;
    // The tangential summary of the final tangential solution.
    let exact_only = TangentialCase {
        method: TangentialMethod::Exact,
        ..*t
    };
    let mut summary = summary_of_exact(&exact_only, &c.tangential);
    summary.outer_iterations = Some(c.outer_iterations);
    summary.tangential_time_s = start.elapsed().as_secs_f64();
    Ok((c.normal, summary, c.tangential))
}

fn summary_of_exact(t: &TangentialCase, sol: &TangentialSolution) -> TangentialSummary {
    let rolling = matches!(t.task, TangentialTask::Rolling(_));
    TangentialSummary {
        tangential_method: t.method.name().into(),
        tangential_problem: if rolling { "rolling" } else { "shift" }.into(),
        mu: t.mu,
        tangential_force_x: sol.force_x,
        tangential_force_y: sol.force_y,
        spin_moment: Some(sol.moment_z),
        adhesion_elements: Some(sol.adhesion_elements),
        slip_elements: Some(sol.slip_elements),
        creepage_x: rolling.then_some(sol.creepages.xi),
        creepage_y: rolling.then_some(sol.creepages.eta),
        spin: rolling.then_some(sol.creepages.phi),
        shift_x: (!rolling).then_some(sol.shift.0),
        shift_y: (!rolling).then_some(sol.shift.1),
        frictional_power: Some(sol.frictional_power),
        tangential_iterations: Some(sol.iterations),
        newton_iterations: Some(sol.newton_iterations),
        outer_iterations: None,
        tangential_time_s: 0.0,
    }
}

/// FASTSIM on the Hertz ellipse (a, b) with the case grid's nx × ny elements.
pub fn fastsim_on(
    case: &PreparedCase,
    mu: f64,
    normal_force: f64,
    a: f64,
    b: f64,
    c: Creepages,
) -> Result<halfspace::FastsimSolution> {
    let input = FastsimInput {
        a,
        b,
        g: case.material.g,
        nu: case.material.nu,
        mu,
        normal_force,
        xi: c.xi,
        eta: c.eta,
        phi: c.phi,
    };
    fastsim(&input, case.grid.nx.max(2), case.grid.ny.max(2)).map_err(|e| anyhow!("FASTSIM: {e}"))
}

/// Solve a prepared case. A non-converged solve is returned with `converged = false`; the
/// caller must report it as a failure.
pub fn solve(case: &PreparedCase) -> Result<CaseOutcome> {
    let mut solver = NormalSolver::new(case.grid, case.material).map_err(|e| anyhow!("{e}"))?;
    let start = Instant::now();
    let solution = match solver.solve(&case.gap, case.load, &case.options) {
        Ok(s) => s,
        Err(ContactError::NotConverged { last, .. }) => *last,
        Err(e) => return Err(anyhow!("{e}")),
    };
    let mut solve_time_s = start.elapsed().as_secs_f64();
    let (solution, tangential_summary, tangential) = match &case.tangential {
        Some(t)
            if solution.converged
                && tangential_strategy(t.method, &case.material) == TangentialStrategy::Coupled =>
        {
            // Dissimilar materials: alternate normal and tangential solves.
            let (n, s, e) = solve_coupled_case(case, t)?;
            solve_time_s = start.elapsed().as_secs_f64();
            (n, Some(s), Some(e))
        }
        Some(t) if solution.converged => {
            let (s, e) = solve_tangential(case, t, &solution)?;
            (solution, Some(s), e)
        }
        _ => (solution, None, None),
    };
    let g = case.grid;
    let m = case.material;
    let hertz_load = match case.load {
        NormalLoad::Force(f) => NormalLoad::Force(f),
        NormalLoad::Approach(_) if solution.normal_force > 0.0 => {
            NormalLoad::Force(solution.normal_force)
        }
        NormalLoad::Approach(d) => NormalLoad::Approach(d),
    };
    let hertz = case
        .shape
        .hertz(&m, hertz_load)
        .map(|h: Hertz| HertzSummary {
            approach: h.approach,
            max_pressure: h.max_pressure,
            a: h.a,
            b: h.b,
            normal_force: h.normal_force,
        });
    let hertz_line = match &case.shape {
        GapShape::Cylinder { radius, length } if solution.normal_force > 0.0 => {
            LineHertz::new(*radius, m.e_star, solution.normal_force / length)
                .ok()
                .map(|l| LineHertzSummary {
                    a: l.a,
                    max_pressure: l.max_pressure,
                    force_per_length: l.force_per_length,
                })
        }
        _ => None,
    };
    let summary = ContactSummary {
        normal_force: solution.normal_force,
        approach: solution.approach,
        max_pressure: solution.max_pressure,
        contact_area: solution.contact_area,
        elements_in_contact: solution.elements_in_contact,
        iterations: solution.iterations,
        residual: solution.residual,
        converged: solution.converged,
        dfn_dapproach: solution.dfn_dapproach,
        solve_time_s,
        centre_of_pressure: [solution.centre_of_pressure.0, solution.centre_of_pressure.1],
        grid: GridSummary {
            nx: g.nx,
            ny: g.ny,
            dx: g.dx,
            dy: g.dy,
            x0: g.x0,
            y0: g.y0,
        },
        material: MaterialSummary {
            g: m.g,
            nu: m.nu,
            k: m.k,
            e_star: m.e_star,
        },
        hertz,
        hertz_line,
        tangential: tangential_summary,
    };
    Ok(CaseOutcome {
        summary,
        solution,
        tangential,
    })
}

/// Human-readable summary.
pub fn print_summary(s: &ContactSummary) {
    println!(
        "normal contact ({} × {} grid, {:.3e} × {:.3e} m elements)",
        s.grid.nx, s.grid.ny, s.grid.dx, s.grid.dy
    );
    println!(
        "  combined G = {:.4e} Pa, nu = {:.4}, K = {:.4}, E* = {:.4e} Pa",
        s.material.g, s.material.nu, s.material.k, s.material.e_star
    );
    println!("  normal force      {:>14.6e} N", s.normal_force);
    println!("  approach          {:>14.6e} m", s.approach);
    println!("  max pressure      {:>14.6e} Pa", s.max_pressure);
    println!(
        "  contact area      {:>14.6e} m^2 ({} elements)",
        s.contact_area, s.elements_in_contact
    );
    println!(
        "  centre of press.  ({:.4e}, {:.4e}) m",
        s.centre_of_pressure[0], s.centre_of_pressure[1]
    );
    if let Some(k) = s.dfn_dapproach {
        println!("  dFn/d(approach)   {:>14.6e} N/m", k);
    }
    println!(
        "  NormCG            {} iterations, relative change {:.2e}, {}, {:.3} ms",
        s.iterations,
        s.residual,
        if s.converged {
            "converged"
        } else {
            "NOT CONVERGED"
        },
        1e3 * s.solve_time_s
    );
    if let Some(h) = &s.hertz {
        println!("Hertz (quadratic gap) at F = {:.6e} N:", h.normal_force);
        println!(
            "  approach {:.6e} m ({:+.3} %), p0 {:.6e} Pa ({:+.3} %), a {:.4e} m, b {:.4e} m",
            h.approach,
            100.0 * (s.approach / h.approach - 1.0),
            h.max_pressure,
            100.0 * (s.max_pressure / h.max_pressure - 1.0),
            h.a,
            h.b
        );
    }
    if let Some(h) = &s.hertz_line {
        println!(
            "Hertz line contact at F' = {:.6e} N/m: a {:.4e} m, p0 {:.6e} Pa ({:+.3} %)",
            h.force_per_length,
            h.a,
            h.max_pressure,
            100.0 * (s.max_pressure / h.max_pressure - 1.0)
        );
    }
    if let Some(t) = &s.tangential {
        println!(
            "tangential contact ({}, {}), mu = {}",
            t.tangential_problem, t.tangential_method, t.mu
        );
        println!(
            "  force x, y        {:>14.6e} N, {:.6e} N  (|F|/(mu Fn) = {:.4})",
            t.tangential_force_x,
            t.tangential_force_y,
            t.tangential_force_x.hypot(t.tangential_force_y) / (t.mu * s.normal_force)
        );
        if let Some(m) = t.spin_moment {
            println!("  spin moment       {m:>14.6e} N m");
        }
        if let (Some(x), Some(y)) = (t.creepage_x, t.creepage_y) {
            println!(
                "  creepages         xi = {x:.6e}, eta = {y:.6e}, spin = {:.6e} 1/m",
                t.spin.unwrap_or(0.0)
            );
        }
        if let (Some(x), Some(y)) = (t.shift_x, t.shift_y) {
            println!("  shift             ({x:.6e}, {y:.6e}) m");
        }
        if let (Some(a), Some(sl)) = (t.adhesion_elements, t.slip_elements) {
            println!("  adhesion / slip   {a} / {sl} elements");
        }
        if let Some(p) = t.frictional_power {
            let unit = if t.tangential_problem == "rolling" {
                "N (power per unit rolling speed)"
            } else {
                "J (work of the shift)"
            };
            println!("  friction loss     {p:>14.6e} {unit}");
        }
        if let Some(o) = t.outer_iterations {
            println!(
                "  K != 0: {o} normal-tangential outer iterations (the normal results above include the coupling)"
            );
        }
        if let Some(i) = t.tangential_iterations {
            println!(
                "  Gauss-Seidel      {i} sweeps, {} Newton iterations, {:.3} ms",
                t.newton_iterations.unwrap_or(0),
                1e3 * t.tangential_time_s
            );
        }
    }
}

/// Write pressure.csv, pressure.png and summary.json into `dir`.
pub fn write_outputs(dir: &Path, outcome: &CaseOutcome) -> Result<()> {
    output::ensure_dir(dir)?;
    let sol = &outcome.solution;
    let g = sol.grid;
    output::write_csv(
        &dir.join("pressure.csv"),
        &["x", "y", "p"],
        (0..g.len()).map(|k| {
            let (x, y) = g.centre(k);
            vec![x, y, sol.pressure[k]]
        }),
    )?;
    let mpa: Vec<f64> = sol.pressure.iter().map(|p| p * 1e-6).collect();
    plot::heatmap(
        &dir.join("pressure.png"),
        "contact pressure",
        "x [mm]",
        "y [mm]",
        "p [MPa]",
        &plot::Field {
            nx: g.nx,
            ny: g.ny,
            x0: g.x0 * 1e3,
            y0: g.y0 * 1e3,
            dx: g.dx * 1e3,
            dy: g.dy * 1e3,
            values: &mpa,
        },
    )?;
    plot::panels(&dir.join("pressure_profile.png"), &[profile_panel(outcome)])?;
    if let Some(t) = &outcome.tangential {
        write_tangential_outputs(dir, t)?;
    }
    output::write_json(&dir.join("summary.json"), &outcome.summary)
}

/// State code of an element in outputs: 0 exterior, 1 adhesion, 2 slip.
fn state_code(s: ElementState) -> f64 {
    match s {
        ElementState::Exterior => 0.0,
        ElementState::Adhesion => 1.0,
        ElementState::Slip => 2.0,
    }
}

/// traction.csv, traction_x.png, traction_y.png and adhesion_slip.png.
fn write_tangential_outputs(dir: &Path, t: &TangentialSolution) -> Result<()> {
    let g = t.grid;
    output::write_csv(
        &dir.join("traction.csv"),
        &["x", "y", "px", "py", "state", "slip_x", "slip_y"],
        (0..g.len()).map(|k| {
            let (x, y) = g.centre(k);
            vec![
                x,
                y,
                t.traction_x[k],
                t.traction_y[k],
                state_code(t.state[k]),
                t.slip_x[k],
                t.slip_y[k],
            ]
        }),
    )?;
    let field = |values: &[f64]| -> Vec<f64> { values.iter().map(|v| v * 1e-6).collect() };
    let (px, py) = (field(&t.traction_x), field(&t.traction_y));
    let states: Vec<f64> = t.state.iter().map(|&s| state_code(s)).collect();
    for (name, title, label, values) in [
        (
            "traction_x.png",
            "tangential traction p_x",
            "p_x [MPa]",
            &px,
        ),
        (
            "traction_y.png",
            "tangential traction p_y",
            "p_y [MPa]",
            &py,
        ),
        (
            "adhesion_slip.png",
            "0 exterior, 1 adhesion, 2 slip",
            "state",
            &states,
        ),
    ] {
        plot::heatmap(
            &dir.join(name),
            title,
            "x [mm]",
            "y [mm]",
            label,
            &plot::Field {
                nx: g.nx,
                ny: g.ny,
                x0: g.x0 * 1e3,
                y0: g.y0 * 1e3,
                dx: g.dx * 1e3,
                dy: g.dy * 1e3,
                values,
            },
        )?;
    }
    Ok(())
}

/// Pressure along x on the grid row through the centre of pressure, with Hertz's profile
/// p₀√(1 − x²/a²) of the same force when the gap is quadratic.
fn profile_panel(outcome: &CaseOutcome) -> plot::Panel {
    let sol = &outcome.solution;
    let g = sol.grid;
    let yc = sol.centre_of_pressure.1;
    let iy = (((yc - g.y0) / g.dy - 0.5).round().max(0.0) as usize).min(g.ny - 1);
    let bem: Vec<(f64, f64)> = (0..g.nx)
        .map(|ix| (g.x(ix) * 1e3, sol.pressure[iy * g.nx + ix] * 1e-6))
        .collect();
    let mut series = vec![plot::Series::new("boundary elements", bem)];
    let hertz_curve = |a: f64, p0: f64| -> Vec<(f64, f64)> {
        (0..=400)
            .map(|k| {
                let x = g.x0 + (g.nx as f64 * g.dx) * k as f64 / 400.0;
                let s = 1.0 - ((x - sol.centre_of_pressure.0) / a).powi(2);
                (x * 1e3, if s > 0.0 { p0 * s.sqrt() * 1e-6 } else { 0.0 })
            })
            .collect()
    };
    if let Some(h) = &outcome.summary.hertz {
        let y = g.y(iy) - yc;
        let scale = (1.0 - (y / h.b).powi(2)).max(0.0).sqrt();
        series.push(plot::Series::new(
            "Hertz",
            hertz_curve(h.a * scale, h.max_pressure * scale),
        ));
    }
    if let Some(h) = &outcome.summary.hertz_line {
        series.push(plot::Series::new(
            "Hertz (line contact)",
            hertz_curve(h.a, h.max_pressure),
        ));
    }
    plot::Panel {
        title: format!("pressure along x at y = {:.4} mm", g.y(iy) * 1e3),
        x_label: "x [mm]".into(),
        y_label: "p [MPa]".into(),
        series,
    }
}
