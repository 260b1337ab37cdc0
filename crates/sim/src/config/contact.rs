//! A quasi-static contact case (`dyncontact contact`, `creep-curve`, `kind = "contact"`):
//! two bodies, a gap, a grid, a load, and optionally friction and kinematics (tangential
//! contact, docs/tangential.md). Every key is in SI units; unknown keys are errors. The
//! schema is in the README.

use std::path::{Path, PathBuf};

use halfspace::{
    Body, GapShape, Grid, Material, NormalLoad, SolverOptions, auto_grid, curvatures_from_radii,
};
use serde::Deserialize;

use super::ConfigError;
use super::checks::{self, MAX_ITERATIONS, ranges};
use super::contact_tangential::tangential_case;
pub use super::contact_tangential::{
    FrictionSpec, KinematicsSpec, TangentialCase, TangentialMethod, TangentialTask,
};

/// Largest `grid.n` of the automatic grid (elements per direction).
pub const MAX_AUTO_GRID_ELEMENTS: usize = 2048;

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
    /// `kind = "wheel_rail"`: wheel profile (built-in name, or a profile file).
    pub wheel: Option<String>,
    /// `kind = "wheel_rail"`: rail profile (built-in name, or a profile file).
    pub rail: Option<String>,
    /// `kind = "wheel_rail"`: rail inclination, "1:20", "1:40", "0" or its tangent.
    pub inclination: Option<toml::Value>,
    /// `kind = "wheel_rail"`: track gauge \[m\].
    pub gauge: Option<f64>,
    /// `kind = "wheel_rail"`: back-to-back distance of the wheels \[m\].
    pub back_to_back: Option<f64>,
    /// `kind = "wheel_rail"`: lateral shift of the wheelset \[m\].
    pub lateral_shift: Option<f64>,
    /// `kind = "wheel_rail"`: nominal rolling radius \[m\].
    pub wheel_radius: Option<f64>,
    /// `kind = "wheel_rail"`: prescribed roll angle \[rad\] (default: both wheels on their rails).
    pub roll: Option<f64>,
    /// `kind = "wheel_rail"`: smoothing parameter λ \[m³\] of measured profiles (default 0).
    pub smoothing: Option<f64>,
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

/// Parse a case file's text (`base` resolves relative table paths).
pub fn parse(text: &str, base: &Path) -> Result<PreparedCase, ConfigError> {
    let case: ContactCase = toml::from_str(text).map_err(|e| {
        ConfigError::Schema(super::with_key_suggestion(format!(
            "invalid case file: {e}"
        )))
    })?;
    prepare(case, base)
}

/// A validated contact case (the `kind = "contact"` scenario of [`super::load`]).
pub type ContactConfig = PreparedCase;

/// Validate a parsed case file (`base` resolves relative table paths).
pub fn build(case: ContactCase, base: &Path) -> Result<ContactConfig, ConfigError> {
    prepare(case, base)
}

fn body(spec: &BodySpec, section: &str) -> Result<Body, ConfigError> {
    if spec.rigid {
        if spec.e.is_some() || spec.nu.is_some() {
            bail!("[{section}]: a rigid body takes no `E` or `nu`");
        }
        return Ok(Body::Rigid);
    }
    let e = spec
        .e
        .ok_or_else(|| invalid!("[{section}]: missing `E` (or set `rigid = true`)"))?;
    let nu = spec
        .nu
        .ok_or_else(|| invalid!("[{section}]: missing `nu`"))?;
    Body::elastic(e, nu).map_err(|err| invalid!("[{section}] {err}"))
}

/// The combined material of `[body1]`, `[body2]` (range-checked).
pub fn checked_material(body1: &BodySpec, body2: &BodySpec) -> Result<Material, ConfigError> {
    let b1 = body(body1, "body1")?;
    let b2 = body(body2, "body2")?;
    let material = Material::combine(b1, b2).map_err(|e| invalid!("[body1]/[body2]: {e}"))?;
    for (key, b) in [("body1", body1), ("body2", body2)] {
        ranges::MODULUS.check_opt(&format!("{key}.E"), b.e)?;
    }
    Ok(material)
}

/// The normal load of `[load]` (exactly one of `force`, `approach`; range-checked).
pub fn checked_load(spec: &LoadSpec) -> Result<NormalLoad, ConfigError> {
    let load = load(spec)?;
    match load {
        NormalLoad::Force(f) => ranges::FORCE.check("load.force", f)?,
        NormalLoad::Approach(d) => ranges::SMALL_DISPLACEMENT.check("load.approach", d)?,
    };
    Ok(load)
}

/// The NormCG options of `[solver]` (range-checked; absent keys keep the defaults).
pub fn solver_options(s: &SolverSpec) -> Result<SolverOptions, ConfigError> {
    let mut options = SolverOptions::default();
    if let Some(tol) = s.tol {
        if !tol.is_finite() || tol <= 0.0 || tol >= 1.0 {
            bail!("[solver] `tol` = {tol}: must lie in (0, 1)");
        }
        ranges::TOLERANCE.check("solver.tol", tol)?;
        options.tol = tol;
    }
    if let Some(m) = s.max_iter {
        if m == 0 {
            bail!("[solver] `max_iter` = 0: must be at least 1");
        }
        options.max_iter = checks::count("solver.max_iter", m, 1, MAX_ITERATIONS)?;
    }
    Ok(options)
}

/// A user-made gap (the Python package's `solve_normal`): the bodies, load and solver
/// options checked as a case file's, the grid as an explicit `[grid]` with `nx`, `ny`, `dx`,
/// `dy` (centred on the origin), and the gap values finite, one per element (row-major, x
/// fastest).
pub struct UserGap {
    /// Combined material.
    pub material: Material,
    /// The grid.
    pub grid: Grid,
    /// The load.
    pub load: NormalLoad,
    /// NormCG options.
    pub options: SolverOptions,
}

/// Checks the inputs of a user-made gap (see [`UserGap`]); `gap` has `ny · nx` values \[m\].
#[allow(clippy::too_many_arguments)]
pub fn user_gap(
    body1: &BodySpec,
    body2: &BodySpec,
    (nx, ny): (usize, usize),
    (dx, dy): (f64, f64),
    gap: &[f64],
    load: &LoadSpec,
    solver: &SolverSpec,
) -> Result<UserGap, ConfigError> {
    let material = checked_material(body1, body2)?;
    let load = checked_load(load)?;
    let spec = GridSpec {
        nx: Some(nx),
        ny: Some(ny),
        dx: Some(dx),
        dy: Some(dy),
        x0: None,
        y0: None,
        n: None,
    };
    let grid = explicit_grid(&spec)?.ok_or_else(|| invalid!("[grid]: missing `nx`"))?;
    if gap.len() != nx * ny {
        bail!(
            "`gap` has {} values, the grid {nx} × {ny} = {}",
            gap.len(),
            nx * ny
        );
    }
    if let Some(k) = gap.iter().position(|h| !h.is_finite()) {
        bail!(
            "`gap` = {} at element (ix, iy) = ({}, {}): must be finite",
            gap[k],
            k % nx,
            k / nx
        );
    }
    let options = solver_options(solver)?;
    Ok(UserGap {
        material,
        grid,
        load,
        options,
    })
}

fn load(spec: &LoadSpec) -> Result<NormalLoad, ConfigError> {
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
fn only_keys(spec: &GapSpec, allowed: &[&str]) -> Result<(), ConfigError> {
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
        ("wheel", spec.wheel.is_some()),
        ("rail", spec.rail.is_some()),
        ("inclination", spec.inclination.is_some()),
        ("gauge", spec.gauge.is_some()),
        ("back_to_back", spec.back_to_back.is_some()),
        ("lateral_shift", spec.lateral_shift.is_some()),
        ("wheel_radius", spec.wheel_radius.is_some()),
        ("roll", spec.roll.is_some()),
        ("smoothing", spec.smoothing.is_some()),
    ];
    for (key, is_set) in present {
        if is_set && !allowed.contains(&key) {
            bail!("[gap] key `{key}` is not used by kind = \"{}\"", spec.kind);
        }
    }
    Ok(())
}

fn required(value: Option<f64>, key: &str) -> Result<f64, ConfigError> {
    value.ok_or_else(|| invalid!("[gap]: missing `{key}`"))
}

fn shape(spec: &GapSpec, grid: Option<&Grid>, base: &Path) -> Result<GapShape, ConfigError> {
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
                .map_err(|e| invalid!("[gap] {e}"))?;
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
                .ok_or_else(|| invalid!("[gap]: missing `file`"))?;
            let grid = grid.ok_or_else(|| {
                invalid!("[gap] kind = \"table\" needs a [grid] with nx, ny, dx, dy")
            })?;
            GapShape::Table {
                values: read_table(&base.join(file), grid)?,
            }
        }
        other => bail!(
            "[gap] `kind` = \"{other}\": expected \"quadratic\", \"sphere\", \"cylinder\", \"punch\", \"table\" or \"wheel_rail\""
        ),
    };
    shape.validate().map_err(|e| invalid!("[gap] {e}"))?;
    check_gap_ranges(spec)?;
    Ok(shape)
}

/// A tabulated gap: a CSV of `ny` lines of `nx` values \[m\]; line k is row iy = k (lowest y
/// first). Lines starting with `#` are comments.
fn read_table(path: &Path, grid: &Grid) -> Result<Vec<f64>, ConfigError> {
    let text = std::fs::read_to_string(path).map_err(|source| ConfigError::Io {
        context: format!("[gap] cannot read `file` {}", path.display()),
        source,
    })?;
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
            .map_err(|e| invalid!("[gap] {} line {}: {e}", path.display(), lineno + 1))?;
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

fn explicit_grid(spec: &GridSpec) -> Result<Option<Grid>, ConfigError> {
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
    let nx = spec.nx.ok_or_else(|| invalid!("[grid]: missing `nx`"))?;
    let ny = spec.ny.ok_or_else(|| invalid!("[grid]: missing `ny`"))?;
    let dx = spec.dx.ok_or_else(|| invalid!("[grid]: missing `dx`"))?;
    let dy = spec.dy.ok_or_else(|| invalid!("[grid]: missing `dy`"))?;
    let x0 = spec.x0.unwrap_or(-0.5 * nx as f64 * dx);
    let y0 = spec.y0.unwrap_or(-0.5 * ny as f64 * dy);
    // The scenario's own checks first: they name the keys as written in the file.
    checks::count("grid.nx", nx, 1, checks::MAX_GRID_SIDE)?;
    checks::count("grid.ny", ny, 1, checks::MAX_GRID_SIDE)?;
    checks::grid("grid.nx × grid.ny", nx, ny)?;
    ranges::ELEMENT_SIZE.check("grid.dx", dx)?;
    ranges::ELEMENT_SIZE.check("grid.dy", dy)?;
    ranges::ORIGIN.check_opt("grid.x0", spec.x0)?;
    ranges::ORIGIN.check_opt("grid.y0", spec.y0)?;
    let grid = Grid::new(nx, ny, dx, dy, x0, y0).map_err(|e| invalid!("[grid] {e}"))?;
    Ok(Some(grid))
}

fn prepare(case: ContactCase, base: &Path) -> Result<PreparedCase, ConfigError> {
    if let Some(kind) = &case.kind
        && kind != "contact"
    {
        bail!("`kind` = \"{kind}\" is not a contact case");
    }
    if case.gap.kind == "wheel_rail" {
        bail!(
            "[gap] kind = \"wheel_rail\" (several contact patches) is solved by `dyncontact contact FILE` and `dyncontact profile-sweep FILE`"
        );
    }
    let material = checked_material(&case.body1, &case.body2)?;
    let load = checked_load(&case.load)?;
    let grid_spec = case.grid.as_ref();
    let explicit = match grid_spec {
        Some(g) => explicit_grid(g)?,
        None => None,
    };
    let shape = shape(&case.gap, explicit.as_ref(), base)?;
    check_patch_within_sphere(&shape, &material, load)?;
    let grid = match explicit {
        Some(g) => g,
        None => {
            let n = grid_spec
                .and_then(|g| g.n)
                .unwrap_or(halfspace::AUTO_GRID_ELEMENTS);
            checks::count("grid.n", n, 1, MAX_AUTO_GRID_ELEMENTS)?;
            checks::grid("grid.n", n, n)?;
            auto_grid(&shape, &material, load, n)
                .map_err(|e| invalid!("[grid] automatic grid: {e}"))?
        }
    };
    let gap = shape.sample(&grid).map_err(|e| invalid!("[gap] {e}"))?;
    let options = match &case.solver {
        Some(s) => solver_options(s)?,
        None => SolverOptions::default(),
    };
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

/// Ranges of the \[gap\] keys that [`GapShape::validate`] accepts (it checks signs).
fn check_gap_ranges(spec: &GapSpec) -> Result<(), ConfigError> {
    ranges::CURVATURE.check_opt("gap.A", spec.a)?;
    ranges::CURVATURE.check_opt("gap.B", spec.b)?;
    for (key, v) in [
        ("gap.R1x", spec.r1x),
        ("gap.R1y", spec.r1y),
        ("gap.R2x", spec.r2x),
        ("gap.R2y", spec.r2y),
    ] {
        // An infinite radius is a flat direction.
        if v.is_some_and(|r| r.is_finite()) {
            checks::Range::symmetric(1e6, "m").check_opt(key, v)?;
        }
    }
    ranges::RADIUS.check_opt("gap.radius", spec.radius)?;
    ranges::RADIUS.check_opt("gap.length", spec.length)?;
    checks::Range::closed(0.0, 1e6, "m").check_opt("gap.edge_radius", spec.edge_radius)?;
    Ok(())
}

/// A sphere's exact gap `R − √(R² − r²)` ends at r = R: a load whose Hertz contact radius
/// reaches R cannot be carried by the sphere (and half-space contact needs a ≪ R long before).
fn check_patch_within_sphere(
    shape: &GapShape,
    material: &Material,
    load: NormalLoad,
) -> Result<(), ConfigError> {
    let GapShape::Sphere { radius } = *shape else {
        return Ok(());
    };
    match shape.hertz(material, load) {
        Some(h) if h.a >= radius => bail!(
            "[load]: the Hertz contact radius at this load, a = {:.4e} m, reaches the sphere's `[gap] radius` = {radius} m (half-space contact needs a ≪ R): lower the load, or check the bodies' E",
            h.a
        ),
        _ => Ok(()),
    }
}
