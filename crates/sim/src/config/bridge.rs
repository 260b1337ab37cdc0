//! The `[bridge]` block of scenario files, shared by `modes`, `kind = "moving_load"` and
//! `kind = "vehicle_bridge"`: an analytic uniform beam, or a finite-element beam when
//! `elements` is given. SI units. Ranges: [`super::checks::ranges`]; `modes` ≤
//! [`MAX_MODES`], `elements` ≤ [`MAX_FE_ELEMENTS`] (checked before the eigen-solve).

use super::ConfigError;
use super::checks::{self, MAX_FE_ELEMENTS, MAX_MODES, ranges};
use beam::{
    AnalyticBeam, FeBeam, ModalBasis, ModalDamping, PointMass, PointSupport, Section, Support,
    SupportKind, UniformBeam,
};
use serde::Deserialize;

/// The `[bridge]` table.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BridgeSpec {
    /// Span length \[m\] (FE: defaults to the sum of the section lengths).
    pub length: Option<f64>,
    /// Bending stiffness EI [N m²] ...
    #[serde(rename = "EI")]
    pub ei: Option<f64>,
    /// ... or Young's modulus E \[Pa\] and second moment of area I \[m⁴\].
    #[serde(rename = "E")]
    pub e: Option<f64>,
    #[serde(rename = "I")]
    pub i: Option<f64>,
    /// Mass per unit length ρA [kg/m].
    pub mass_per_length: Option<f64>,
    /// Analytic model: simply_supported | clamped_clamped | clamped_free | clamped_pinned | free_free.
    pub supports: Option<String>,
    /// Number of modes.
    pub modes: Option<usize>,
    /// One damping ratio for every mode (default 0).
    pub damping_ratio: Option<f64>,
    /// One damping ratio per mode.
    pub damping_ratios: Option<Vec<f64>>,
    /// Rayleigh damping [α (1/s), β (s)]: C = α M + β K.
    pub rayleigh: Option<[f64; 2]>,
    /// FE model: number of elements (selects the finite-element beam).
    pub elements: Option<usize>,
    /// FE model: positions of pinned supports \[m\].
    pub supports_at: Option<Vec<f64>>,
    /// FE model: positions of clamped supports \[m\].
    pub clamped_at: Option<Vec<f64>>,
    /// FE model: sections from x = 0 (default: one uniform section).
    pub sections: Option<Vec<SectionSpec>>,
    /// FE model: elastic bearings.
    pub bearings: Option<Vec<BearingSpec>>,
    /// FE model: point masses.
    pub point_masses: Option<Vec<PointMassSpec>>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SectionSpec {
    pub length: f64,
    #[serde(rename = "EI")]
    pub ei: Option<f64>,
    #[serde(rename = "E")]
    pub e: Option<f64>,
    #[serde(rename = "I")]
    pub i: Option<f64>,
    pub mass_per_length: f64,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BearingSpec {
    pub x: f64,
    /// Translational stiffness [N/m].
    pub translational: f64,
    /// Rotational stiffness [N m/rad] (default 0).
    #[serde(default)]
    pub rotational: f64,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointMassSpec {
    pub x: f64,
    pub mass: f64,
    #[serde(default)]
    pub rotary_inertia: f64,
}

/// A bridge ready for modal computations.
pub struct Bridge {
    /// The mass-normalised modal basis (analytic or FE).
    pub basis: Box<dyn ModalBasis + Send + Sync>,
    /// Modal damping.
    pub damping: ModalDamping,
    /// Reference uniform properties (the single section of an analytic beam, or the first FE
    /// section), used for βL and closed forms.
    pub reference: UniformBeam,
    /// The analytic support, if the analytic model is used.
    pub support: Option<Support>,
    /// The analytic characteristic roots β_n L (analytic model only).
    pub roots: Option<Vec<f64>>,
    /// One-line description for reports.
    pub description: String,
    /// The positions of an FE beam's point supports (pinned, clamped, elastic), sorted, each
    /// once \[m\] (empty for an analytic beam, whose supports are its ends).
    pub support_positions: Vec<f64>,
}

/// EI from `EI` or `E` × `I`; `at` is the section as printed, `path` the key prefix
/// (`bridge` or `bridge.sections[k]`). Every value is range-checked under the key as written
/// (`bridge.EI`, `bridge.E`, `bridge.I`), zero and negative ones included.
fn bending_stiffness(
    ei: Option<f64>,
    e: Option<f64>,
    i: Option<f64>,
    at: &str,
    path: &str,
) -> Result<f64, ConfigError> {
    let positive_out_of_range = |key: &str, v: f64, range: checks::Range| {
        range.check(&format!("{path}.{key}"), v).map(|_| ())
    };
    match (ei, e, i) {
        (Some(ei), None, None) => {
            positive_out_of_range("EI", ei, ranges::BENDING_STIFFNESS)?;
            Ok(ei)
        }
        (None, Some(e), Some(i)) => {
            positive_out_of_range("E", e, ranges::MODULUS)?;
            positive_out_of_range("I", i, ranges::SECOND_MOMENT)?;
            Ok(e * i)
        }
        (Some(_), _, _) => bail!("{at}: give either `EI` or `E` and `I`, not both"),
        (None, Some(_), None) => bail!("{at}: `E` needs `I`"),
        (None, None, Some(_)) => bail!("{at}: `I` needs `E`"),
        (None, None, None) => bail!("{at}: missing bending stiffness `EI` (or `E` and `I`)"),
    }
}

fn support_by_name(name: &str) -> Result<Support, ConfigError> {
    Ok(match name {
        "simply_supported" => Support::SimplySupported,
        "clamped_clamped" => Support::ClampedClamped,
        "clamped_free" => Support::ClampedFree,
        "clamped_pinned" => Support::ClampedPinned,
        "free_free" => Support::FreeFree,
        other => bail!(
            "[bridge] `supports` = \"{other}\": expected simply_supported, clamped_clamped, clamped_free, clamped_pinned or free_free"
        ),
    })
}

fn damping(spec: &BridgeSpec, n_modes: usize) -> Result<ModalDamping, ConfigError> {
    let given = [
        spec.damping_ratio.is_some(),
        spec.damping_ratios.is_some(),
        spec.rayleigh.is_some(),
    ];
    if given.iter().filter(|g| **g).count() > 1 {
        bail!("[bridge]: give at most one of `damping_ratio`, `damping_ratios`, `rayleigh`");
    }
    if let Some(z) = spec.damping_ratio {
        if !z.is_finite() || z < 0.0 {
            bail!("[bridge] `damping_ratio` = {z}: must be a non-negative number");
        }
        ranges::DAMPING_RATIO.check("bridge.damping_ratio", z)?;
        return Ok(if z == 0.0 {
            ModalDamping::Undamped
        } else {
            ModalDamping::Uniform(z)
        });
    }
    if let Some(zs) = &spec.damping_ratios {
        if zs.len() != n_modes {
            bail!(
                "[bridge] `damping_ratios` has {} values, `modes` = {n_modes}",
                zs.len()
            );
        }
        if let Some(z) = zs.iter().find(|z| !z.is_finite() || **z < 0.0) {
            bail!("[bridge] `damping_ratios` contains {z}: ratios must be non-negative");
        }
        for (k, z) in zs.iter().enumerate() {
            ranges::DAMPING_RATIO.check(&format!("bridge.damping_ratios[{k}]"), *z)?;
        }
        return Ok(ModalDamping::PerMode(zs.clone()));
    }
    if let Some([a, b]) = spec.rayleigh {
        if !(a.is_finite() && b.is_finite() && a >= 0.0 && b >= 0.0) {
            bail!("[bridge] `rayleigh` = [{a}, {b}]: coefficients must be non-negative");
        }
        checks::Range::closed(0.0, 1e6, "1/s").check("bridge.rayleigh[0]", a)?;
        checks::Range::closed(0.0, 1.0, "s").check("bridge.rayleigh[1]", b)?;
        return Ok(ModalDamping::Rayleigh {
            mass_coefficient: a,
            stiffness_coefficient: b,
        });
    }
    Ok(ModalDamping::Undamped)
}

impl BridgeSpec {
    /// Range checks of the scalar keys (positive values out of range; signs and zeros are
    /// left to the beam constructors, whose messages are kept).
    fn check_ranges(&self) -> Result<(), ConfigError> {
        let positive = |key: &str, v: Option<f64>, range: checks::Range| match v {
            Some(v) if v > 0.0 || !v.is_finite() => range.check(key, v).map(|_| ()),
            _ => Ok(()),
        };
        positive("bridge.length", self.length, ranges::SPAN)?;
        positive(
            "bridge.mass_per_length",
            self.mass_per_length,
            ranges::MASS_PER_LENGTH,
        )?;
        for (k, s) in self.sections.iter().flatten().enumerate() {
            ranges::SPAN.check(&format!("bridge.sections[{k}].length"), s.length)?;
            ranges::MASS_PER_LENGTH.check(
                &format!("bridge.sections[{k}].mass_per_length"),
                s.mass_per_length,
            )?;
        }
        for (key, list) in [
            ("bridge.supports_at", &self.supports_at),
            ("bridge.clamped_at", &self.clamped_at),
        ] {
            for (k, x) in list.iter().flatten().enumerate() {
                ranges::POSITION.check(&format!("{key}[{k}]"), *x)?;
            }
        }
        for (k, b) in self.bearings.iter().flatten().enumerate() {
            ranges::POSITION.check(&format!("bridge.bearings[{k}].x"), b.x)?;
            ranges::STIFFNESS.check(
                &format!("bridge.bearings[{k}].translational"),
                b.translational,
            )?;
            ranges::ROTATIONAL_STIFFNESS
                .check(&format!("bridge.bearings[{k}].rotational"), b.rotational)?;
        }
        for (k, m) in self.point_masses.iter().flatten().enumerate() {
            ranges::POSITION.check(&format!("bridge.point_masses[{k}].x"), m.x)?;
            ranges::MASS_OR_ZERO.check(&format!("bridge.point_masses[{k}].mass"), m.mass)?;
            ranges::INERTIA.check(
                &format!("bridge.point_masses[{k}].rotary_inertia"),
                m.rotary_inertia,
            )?;
        }
        Ok(())
    }

    /// Build the modal model.
    pub fn build(&self) -> Result<Bridge, ConfigError> {
        let n_modes = self
            .modes
            .ok_or_else(|| invalid!("[bridge]: missing `modes` (number of modes)"))?;
        if n_modes == 0 {
            bail!("[bridge] `modes` = 0: at least one mode is needed");
        }
        checks::count("bridge.modes", n_modes, 1, MAX_MODES)?;
        self.check_ranges()?;
        let damping = damping(self, n_modes)?;
        if self.elements.is_some() {
            self.build_fe(n_modes, damping)
        } else {
            self.build_analytic(n_modes, damping)
        }
    }

    fn build_analytic(&self, n_modes: usize, damping: ModalDamping) -> Result<Bridge, ConfigError> {
        for (key, set) in [
            ("supports_at", self.supports_at.is_some()),
            ("clamped_at", self.clamped_at.is_some()),
            ("sections", self.sections.is_some()),
            ("bearings", self.bearings.is_some()),
            ("point_masses", self.point_masses.is_some()),
        ] {
            if set {
                bail!(
                    "[bridge] `{key}` belongs to the finite-element model: set `elements` to use it"
                );
            }
        }
        let length = self
            .length
            .ok_or_else(|| invalid!("[bridge]: missing `length`"))?;
        let ei = bending_stiffness(self.ei, self.e, self.i, "[bridge]", "bridge")?;
        let mass = self
            .mass_per_length
            .ok_or_else(|| invalid!("[bridge]: missing `mass_per_length`"))?;
        let support = support_by_name(self.supports.as_deref().unwrap_or("simply_supported"))?;
        let uniform = UniformBeam::new(length, ei, mass).map_err(|e| invalid!("[bridge] {e}"))?;
        let basis =
            AnalyticBeam::new(support, uniform, n_modes).map_err(|e| invalid!("[bridge] {e}"))?;
        let roots = basis.roots().to_vec();
        Ok(Bridge {
            basis: Box::new(basis),
            damping,
            reference: uniform,
            support: Some(support),
            roots: Some(roots),
            description: format!(
                "analytic {} beam, L = {length} m, EI = {ei:.4e} N m², ρA = {mass} kg/m, {n_modes} modes",
                self.supports.as_deref().unwrap_or("simply_supported")
            ),
            support_positions: Vec::new(),
        })
    }

    fn build_fe(&self, n_modes: usize, damping: ModalDamping) -> Result<Bridge, ConfigError> {
        if self.supports.is_some() {
            bail!(
                "[bridge] `supports` is for the analytic model; the FE model uses `supports_at`, `clamped_at`, `bearings`"
            );
        }
        let elements = self.elements.unwrap_or(0);
        checks::count("bridge.elements", elements, 1, MAX_FE_ELEMENTS)?;
        // The dense eigen-solve: about six n × n matrices of the n = 2 (elements + 1) DOFs.
        let dofs = 2.0 * (elements as f64 + 1.0);
        checks::memory(
            &format!("`bridge.elements` = {elements} (dense eigen-solve)"),
            dofs * dofs,
            6.0 * 8.0,
        )?;
        let sections: Vec<Section> = match &self.sections {
            Some(list) => {
                if self.ei.is_some()
                    || self.e.is_some()
                    || self.i.is_some()
                    || self.mass_per_length.is_some()
                {
                    bail!(
                        "[bridge]: with [[bridge.sections]] give EI and mass_per_length per section, not in [bridge]"
                    );
                }
                list.iter()
                    .enumerate()
                    .map(|(k, s)| {
                        Ok(Section {
                            length: s.length,
                            bending_stiffness: bending_stiffness(
                                s.ei,
                                s.e,
                                s.i,
                                &format!("[[bridge.sections]] #{}", k + 1),
                                &format!("bridge.sections[{k}]"),
                            )?,
                            mass_per_length: s.mass_per_length,
                        })
                    })
                    .collect::<Result<_, ConfigError>>()?
            }
            None => vec![Section {
                length: self
                    .length
                    .ok_or_else(|| invalid!("[bridge]: missing `length`"))?,
                bending_stiffness: bending_stiffness(
                    self.ei, self.e, self.i, "[bridge]", "bridge",
                )?,
                mass_per_length: self
                    .mass_per_length
                    .ok_or_else(|| invalid!("[bridge]: missing `mass_per_length`"))?,
            }],
        };
        let total: f64 = sections.iter().map(|s| s.length).sum();
        if let Some(l) = self.length
            && self.sections.is_some()
            && (l - total).abs() > 1e-9 * total
        {
            bail!("[bridge] `length` = {l} differs from the sum of the section lengths {total}");
        }
        let mut supports = Vec::new();
        for &x in self.supports_at.iter().flatten() {
            supports.push(PointSupport {
                x,
                kind: SupportKind::Pinned,
            });
        }
        for &x in self.clamped_at.iter().flatten() {
            supports.push(PointSupport {
                x,
                kind: SupportKind::Clamped,
            });
        }
        for b in self.bearings.iter().flatten() {
            supports.push(PointSupport {
                x: b.x,
                kind: SupportKind::Spring {
                    translational: b.translational,
                    rotational: b.rotational,
                },
            });
        }
        let masses: Vec<PointMass> = self
            .point_masses
            .iter()
            .flatten()
            .map(|m| PointMass {
                x: m.x,
                mass: m.mass,
                rotary_inertia: m.rotary_inertia,
            })
            .collect();
        let fe = FeBeam::new(&sections, &supports, &masses, elements)
            .map_err(|e| invalid!("[bridge] {e}"))?;
        let modes = fe
            .modes(n_modes)
            .map_err(|e| invalid!("[bridge] FE eigen-solve: {e}"))?;
        let first = sections[0];
        let reference = UniformBeam::new(total, first.bending_stiffness, first.mass_per_length)
            .map_err(|e| invalid!("[bridge] {e}"))?;
        Ok(Bridge {
            basis: Box::new(modes),
            damping,
            reference,
            support: None,
            roots: None,
            description: format!(
                "finite-element beam, L = {total} m, {} sections, {elements} elements, {} supports, {n_modes} modes",
                sections.len(),
                supports.len()
            ),
            support_positions: {
                let mut xs: Vec<f64> = supports.iter().map(|s| s.x).collect();
                xs.sort_by(f64::total_cmp);
                xs.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * total);
                xs
            },
        })
    }
}

impl Bridge {
    /// The midpoint of each span between consecutive supports \[m\] (an analytic beam, or an
    /// FE beam with fewer than two supports: L/2): the default output points of a sweep.
    pub fn span_midpoints(&self) -> Vec<f64> {
        let mids: Vec<f64> = self
            .support_positions
            .windows(2)
            .map(|w| 0.5 * (w[0] + w[1]))
            .collect();
        if mids.is_empty() {
            vec![0.5 * self.basis.length()]
        } else {
            mids
        }
    }

    /// The midspans of a continuous bridge's spans other than the one at `x` (empty for a
    /// single span): the default extra response points of `vehicle_bridge` and `moving_load`,
    /// so that every span is reported.
    pub fn other_span_midpoints(&self, x: f64) -> Vec<f64> {
        let length = self.basis.length();
        let mids = self.span_midpoints();
        if mids.len() < 2 {
            return Vec::new();
        }
        mids.into_iter()
            .filter(|m| (m - x).abs() > 1e-9 * length)
            .collect()
    }

    /// The default output point of a single-point run (`vehicle_bridge`): the bridge's middle
    /// L/2, unless that is a support of a continuous FE bridge (where the deck does not move):
    /// then the midspan of its longest span (the first of equal ones), with a note saying so.
    pub fn default_output_point(&self) -> (f64, Option<String>) {
        let length = self.basis.length();
        let middle = 0.5 * length;
        if !self
            .support_positions
            .iter()
            .any(|&x| (x - middle).abs() <= 1e-9 * length)
        {
            return (middle, None);
        }
        let (mut best, mut span) = (middle, 0.0);
        for w in self.support_positions.windows(2) {
            if w[1] - w[0] > span + 1e-9 * length {
                (best, span) = (0.5 * (w[0] + w[1]), w[1] - w[0]);
            }
        }
        (
            best,
            Some(format!(
                "the output point is x = {best} m, the midspan of the longest span: the bridge's middle x = {middle} m is a support, where the deck does not move (set [output] point to choose)"
            )),
        )
    }

    /// β_n L of mode n: the analytic root, or for FE modes the value implied by ω_n and the
    /// reference section, (ω_n² ρA L⁴ / EI)^{1/4}.
    pub fn beta_l(&self, j: usize) -> f64 {
        match &self.roots {
            Some(r) => r[j],
            None => {
                let b = self.reference;
                let w = self.basis.circular_frequencies()[j];
                (w * w * b.mass_per_length * b.length.powi(4) / b.bending_stiffness).powf(0.25)
            }
        }
    }
}

/// A file read by `dyncontact modes`: a `[bridge]` section, alone or in a scenario.
#[derive(Deserialize)]
struct BridgeFile {
    kind: Option<String>,
    bridge: Option<toml::Value>,
    #[serde(flatten)]
    other: toml::Table,
}

/// The bridge of a file's `[bridge]` section. Other top-level keys are accepted only in a
/// scenario file (one with `kind`), where they belong to the scenario.
pub fn parse_bridge_file(text: &str) -> Result<Bridge, ConfigError> {
    let file: BridgeFile = toml::from_str(text)
        .map_err(|e| ConfigError::Schema(format!("invalid bridge file: {e}")))?;
    if file.kind.is_none()
        && let Some(other) = file.other.keys().next()
    {
        bail!(
            "unknown key `{other}`: a bridge file holds only a [bridge] section (or is a scenario with `kind`)"
        );
    }
    let spec: BridgeSpec = file
        .bridge
        .ok_or_else(|| invalid!("missing [bridge] section"))?
        .try_into()
        .map_err(|e: toml::de::Error| {
            ConfigError::Schema(super::with_key_suggestion(format!(
                "[bridge]: {}",
                e.message()
            )))
        })?;
    spec.build()
}
