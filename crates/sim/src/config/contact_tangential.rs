//! The `[friction]` and `[kinematics]` tables of a contact case (module [`super::contact`]):
//! the tangential problem (steady rolling or shift, creepages or prescribed forces, the
//! method), validated. SI units; docs/tangential.md.

use halfspace::{Creepages, RollingLoad, ShiftLoad};
use serde::Deserialize;

use super::ConfigError;
use super::checks::ranges;

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

fn finite_key(section: &str, key: &str, value: Option<f64>) -> Result<Option<f64>, ConfigError> {
    match value {
        Some(v) if !v.is_finite() => bail!("[{section}] `{key}` = {v}: must be a finite number"),
        other => Ok(other),
    }
}

/// Validate \[friction\] and \[kinematics\].
pub(crate) fn tangential_case(
    friction: Option<&FrictionSpec>,
    kin: Option<&KinematicsSpec>,
) -> Result<(Option<f64>, Option<TangentialCase>), ConfigError> {
    let mu = match friction {
        None => None,
        Some(f) => {
            let mu = f.mu.ok_or_else(|| {
                invalid!("[friction]: missing `mu` (Coulomb friction coefficient)")
            })?;
            if !mu.is_finite() || mu <= 0.0 {
                bail!("[friction] `mu` = {mu}: must be a positive number");
            }
            ranges::FRICTION.check("friction.mu", mu)?;
            Some(mu)
        }
    };
    let Some(k) = kin else {
        return Ok((mu, None));
    };
    let mu = mu.ok_or_else(|| invalid!("[kinematics] needs a [friction] section with `mu`"))?;
    let cx = finite_key("kinematics", "creepage_x", k.creepage_x)?;
    let cy = finite_key("kinematics", "creepage_y", k.creepage_y)?;
    let spin = finite_key("kinematics", "spin", k.spin)?;
    let sx = finite_key("kinematics", "shift_x", k.shift_x)?;
    let sy = finite_key("kinematics", "shift_y", k.shift_y)?;
    let fx = finite_key("kinematics", "force_x", k.force_x)?;
    let fy = finite_key("kinematics", "force_y", k.force_y)?;
    ranges::CREEPAGE.check_opt("kinematics.creepage_x", cx)?;
    ranges::CREEPAGE.check_opt("kinematics.creepage_y", cy)?;
    ranges::SPIN.check_opt("kinematics.spin", spin)?;
    ranges::SMALL_DISPLACEMENT.check_opt("kinematics.shift_x", sx)?;
    ranges::SMALL_DISPLACEMENT.check_opt("kinematics.shift_y", sy)?;
    ranges::FORCE.check_opt("kinematics.force_x", fx)?;
    ranges::FORCE.check_opt("kinematics.force_y", fy)?;
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
