//! `kind = "ball_drop"`: a ball dropped on an elastic half-space (Hertz or boundary-element
//! contact, any integrator). The schema is documented in docs/ball_drop.md. SI units; unknown
//! keys are errors.

use halfspace::Body;
use serde::Deserialize;

use super::checks::{self, ranges};
use super::integrator::StructuralParameters;
use super::{ConfigError, suggestion};
use crate::ball_drop::{
    BallDrop, BallShape, ForceModel, Integrator, IntegratorSettings, METHOD_NAMES, sphere_mass,
};

/// Default simulated time \[s\].
pub const DEFAULT_DURATION: f64 = 1.0;
/// Default gravitational acceleration \[m/s²\].
pub const DEFAULT_GRAVITY: f64 = 9.81;
/// Default integrator: Radau5, adaptive (rtol 1e-8, atol 1e-12: the first peak force of the
/// steel-ball drop within 1e-6 of the closed form, docs/ball_drop.md).
pub const DEFAULT_METHOD: &str = "radau5";
/// Default boundary-element grid of `model = "bem"` (elements per side).
pub const DEFAULT_BEM_ELEMENTS: usize = 32;
/// Default NormCG tolerance of `model = "bem"`.
pub const DEFAULT_BEM_TOL: f64 = 1e-10;
/// Longest simulated time \[s\]: a ball that has come to rest keeps an adaptive method
/// stepping at the contact time scale, so longer runs are refused up front.
pub const MAX_DURATION: f64 = 1e3;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BallDropFile {
    pub kind: String,
    /// Simulated time \[s\] (default 1.0).
    pub duration: Option<f64>,
    /// Gravitational acceleration [m/s²] (default 9.81).
    pub gravity: Option<f64>,
    pub ball: BallSpec,
    pub surface: SurfaceSpec,
    pub initial: InitialSpec,
    pub contact: Option<ContactSpec>,
    pub integrator: Option<IntegratorSpec>,
    pub output: Option<OutputSpec>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BallSpec {
    pub radius: Option<f64>,
    pub radius_x: Option<f64>,
    pub radius_y: Option<f64>,
    pub density: Option<f64>,
    pub mass: Option<f64>,
    pub rigid: Option<bool>,
    #[serde(rename = "E")]
    pub e: Option<f64>,
    pub nu: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SurfaceSpec {
    pub rigid: Option<bool>,
    #[serde(rename = "E")]
    pub e: Option<f64>,
    pub nu: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InitialSpec {
    pub height: f64,
    pub velocity: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    pub model: Option<String>,
    pub damping: Option<f64>,
    pub elements: Option<usize>,
    pub tol: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IntegratorSpec {
    pub method: Option<String>,
    pub rtol: Option<f64>,
    pub atol: Option<f64>,
    pub dt: Option<f64>,
    pub dt_flight: Option<f64>,
    pub guard_step: Option<f64>,
    pub max_step: Option<f64>,
    pub alpha: Option<f64>,
    pub rho_inf: Option<f64>,
    pub beta: Option<f64>,
    pub gamma: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    pub interval: Option<f64>,
    pub plot: Option<bool>,
}

/// A validated ball-drop scenario.
#[derive(Debug, Clone, PartialEq)]
pub struct BallDropConfig {
    /// The scenario.
    pub scenario: BallDrop,
    /// Write the plot (`output.plot`, default true).
    pub plot: bool,
    /// The integrator settings used (rtol, atol, dt), for the summary.
    pub settings: (Option<f64>, Option<f64>, Option<f64>),
}

fn body(
    section: &str,
    rigid: Option<bool>,
    e: Option<f64>,
    nu: Option<f64>,
) -> Result<Body, ConfigError> {
    match (rigid.unwrap_or(false), e, nu) {
        (true, None, None) => Ok(Body::Rigid),
        (true, _, _) => bail!("[{section}]: a rigid body takes no `E` or `nu`"),
        (false, Some(e), Some(nu)) => {
            Body::elastic(e, nu).map_err(|err| invalid!("[{section}] {err}"))
        }
        (false, None, _) => bail!("[{section}]: missing `E` [Pa] (or set `rigid = true`)"),
        (false, Some(_), None) => bail!("[{section}]: missing `nu`"),
    }
}

/// Parse a scenario file's text; `integrator` overrides `[integrator] method`.
pub fn parse(text: &str, integrator: Option<&str>) -> Result<BallDropConfig, ConfigError> {
    build(super::from_str(text)?, integrator)
}

/// Validate a parsed file; `integrator` overrides `[integrator] method`.
pub fn build(s: BallDropFile, integrator: Option<&str>) -> Result<BallDropConfig, ConfigError> {
    if s.kind != "ball_drop" {
        bail!("`kind` = \"{}\" is not a ball-drop scenario", s.kind);
    }
    let b = &s.ball;
    let shape = match (b.radius, b.radius_x, b.radius_y) {
        (Some(radius), None, None) => BallShape::Sphere { radius },
        (None, Some(radius_x), Some(radius_y)) => BallShape::Ellipsoid { radius_x, radius_y },
        (None, None, None) => bail!("[ball]: missing `radius` (or `radius_x` and `radius_y`)"),
        (Some(_), _, _) => {
            bail!("[ball]: give either `radius` or `radius_x` and `radius_y`, not both")
        }
        (None, _, _) => bail!("[ball]: an ellipsoid needs both `radius_x` and `radius_y`"),
    };
    let mass = match (b.mass, b.density, shape) {
        (Some(m), None, _) => m,
        (None, Some(rho), BallShape::Sphere { radius }) => {
            if !(rho.is_finite() && rho > 0.0) {
                bail!("[ball] `density` = {rho}: must be finite and > 0 [kg/m³]");
            }
            ranges::DENSITY.check("ball.density", rho)?;
            sphere_mass(radius, rho)
        }
        (None, Some(_), BallShape::Ellipsoid { .. }) => {
            bail!("[ball]: `density` needs a sphere (`radius`); give the `mass` of an ellipsoid")
        }
        (Some(_), Some(_), _) => bail!("[ball]: give either `mass` or `density`, not both"),
        (None, None, _) => bail!("[ball]: missing `mass` [kg] or `density` [kg/m³]"),
    };
    let ball = body("ball", b.rigid, b.e, b.nu)?;
    let surface = body("surface", s.surface.rigid, s.surface.e, s.surface.nu)?;
    let c = s.contact.as_ref();
    let model_name = c.and_then(|c| c.model.as_deref()).unwrap_or("hertz");
    let model = match model_name {
        "hertz" => {
            if c.is_some_and(|c| c.elements.is_some() || c.tol.is_some()) {
                bail!("[contact]: `elements` and `tol` belong to model = \"bem\"");
            }
            ForceModel::Hertz
        }
        "bem" => ForceModel::Bem {
            elements: c.and_then(|c| c.elements).unwrap_or(DEFAULT_BEM_ELEMENTS),
            tol: c.and_then(|c| c.tol).unwrap_or(DEFAULT_BEM_TOL),
        },
        other => bail!("[contact] `model` = \"{other}\": expected \"hertz\" or \"bem\""),
    };
    let i = s.integrator.as_ref();
    let method = integrator
        .or_else(|| i.and_then(|i| i.method.as_deref()))
        .unwrap_or(DEFAULT_METHOD);
    let defaults = IntegratorSettings::default();
    let parameters = StructuralParameters {
        beta: i.and_then(|i| i.beta),
        gamma: i.and_then(|i| i.gamma),
        alpha: i.and_then(|i| i.alpha),
        rho_inf: i.and_then(|i| i.rho_inf),
    }
    .list()?;
    let settings = IntegratorSettings {
        rtol: i.and_then(|i| i.rtol).unwrap_or(defaults.rtol),
        atol: i.and_then(|i| i.atol).unwrap_or(defaults.atol),
        dt: i.and_then(|i| i.dt).unwrap_or(defaults.dt),
        dt_flight: i.and_then(|i| i.dt_flight),
        guard_step: i.and_then(|i| i.guard_step),
        max_step: i.and_then(|i| i.max_step),
        parameters,
    };
    if integrate::ode::Method::from_name(method).is_err()
        && integrate::structural::StructuralMethod::by_name(method, &[]).is_err()
    {
        bail!(
            "[integrator] method = \"{method}\": unknown method (known: {}){}",
            METHOD_NAMES.join(", "),
            suggestion(method, &METHOD_NAMES)
        );
    }
    let integrator = Integrator::from_name(method, &settings).map_err(|e| {
        invalid!(
            "[integrator] method = \"{method}\" (known: {}): {e}",
            METHOD_NAMES.join(", ")
        )
    })?;
    let scenario = BallDrop {
        mass,
        shape,
        ball,
        surface,
        gravity: s.gravity.unwrap_or(DEFAULT_GRAVITY),
        height: s.initial.height,
        velocity: s.initial.velocity.unwrap_or(0.0),
        duration: s.duration.unwrap_or(DEFAULT_DURATION),
        model,
        damping: c.and_then(|c| c.damping).unwrap_or(0.0),
        integrator,
        output_interval: s.output.as_ref().and_then(|o| o.interval),
    };
    scenario.validate().map_err(|e| invalid!("{e}"))?;
    check_ranges(&scenario)?;
    Ok(BallDropConfig {
        scenario,
        plot: s.output.as_ref().and_then(|o| o.plot).unwrap_or(true),
        settings: (Some(settings.rtol), Some(settings.atol), Some(settings.dt)),
    })
}

/// Physical ranges of the keys [`BallDrop::validate`] accepts (it checks signs and
/// finiteness), and the run length.
fn check_ranges(s: &BallDrop) -> Result<(), ConfigError> {
    ranges::MASS.check("ball.mass", s.mass)?;
    match s.shape {
        BallShape::Sphere { radius } => {
            ranges::RADIUS.check("ball.radius", radius)?;
        }
        BallShape::Ellipsoid { radius_x, radius_y } => {
            ranges::RADIUS.check("ball.radius_x", radius_x)?;
            ranges::RADIUS.check("ball.radius_y", radius_y)?;
        }
    }
    for (key, body) in [("ball", s.ball), ("surface", s.surface)] {
        if let Body::Elastic { e, .. } = body {
            ranges::MODULUS.check(&format!("{key}.E"), e)?;
        }
    }
    ranges::GRAVITY.check("gravity", s.gravity)?;
    checks::Range::closed(0.0, 1e4, "m").check("initial.height", s.height)?;
    ranges::VELOCITY.check("initial.velocity", s.velocity)?;
    checks::Range::above(0.0, MAX_DURATION, "s").check("duration", s.duration)?;
    checks::Range::closed(0.0, 1e12, "N s/m").check("contact.damping", s.damping)?;
    if let ForceModel::Bem { tol, .. } = s.model {
        ranges::TOLERANCE.check("contact.tol", tol)?;
    }
    let interval = s
        .output_interval
        .map(|h| ranges::TIME_STEP.check("output.interval", h))
        .transpose()?;
    match s.integrator {
        Integrator::Ode {
            rtol,
            atol,
            dt,
            guard_step,
            max_step,
            ..
        } => {
            if s.integrator.is_adaptive() {
                ranges::TOLERANCE.check("integrator.rtol", rtol)?;
                // atol = 0 leaves no error scale for a state component at 0 (the dissipated
                // energy starts at 0, a dropped ball at rest has v = 0): the step-size control
                // divides by zero.
                ranges::ABS_TOLERANCE.check("integrator.atol", atol)?;
            } else {
                ranges::TIME_STEP.check("integrator.dt", dt)?;
                checks::steps("duration / integrator.dt", s.duration / dt)?;
            }
            for (key, h) in [
                ("integrator.guard_step", guard_step),
                ("integrator.max_step", max_step),
            ] {
                ranges::TIME_STEP.check_opt(key, h)?;
            }
        }
        Integrator::Structural { dt, dt_flight, .. } => {
            ranges::TIME_STEP.check("integrator.dt", dt)?;
            ranges::TIME_STEP.check("integrator.dt_flight", dt_flight)?;
            checks::steps("duration / integrator.dt_flight", s.duration / dt_flight)?;
        }
    }
    if let Some(h) = interval {
        checks::output_rows("duration / output.interval", s.duration / h)?;
    }
    Ok(())
}
