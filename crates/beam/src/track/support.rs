//! The discrete support under the rail at one sleeper (or fastener): a chain of spring–dampers
//! and lumped masses from the rail down to the foundation (references.md §D5.2).
//!
//! ```text
//! rail ──spring 0── body 0 ──spring 1── body 1 … body n−1 ──spring n── foundation
//! ```
//!
//! A ballasted track is pad → sleeper → ballast (→ ballast mass → subgrade); a direct-fastened
//! (ballastless) track on a deck is a single pad spring; a slab track is pad → slab → CA layer.

use crate::error::{BeamError, non_negative, positive};

/// A linear spring with a parallel viscous damper: stiffness \[N/m\], damping \[N s/m\].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpringDamper {
    /// Stiffness \[N/m\] (> 0).
    pub stiffness: f64,
    /// Viscous damping \[N s/m\] (≥ 0).
    pub damping: f64,
}

impl SpringDamper {
    /// A spring–damper, validated (stiffness > 0, damping ≥ 0, both finite).
    pub fn new(stiffness: f64, damping: f64) -> Result<Self, BeamError> {
        positive("stiffness", stiffness)?;
        non_negative("damping", damping)?;
        Ok(Self { stiffness, damping })
    }
}

/// The support chain at one sleeper: `springs[0]` connects the rail to `masses[0]` (or to the
/// foundation when there are no masses), `springs[i]` connects `masses[i − 1]` to `masses[i]`,
/// and the last spring connects the last mass to the foundation. So
/// `springs.len() == masses.len() + 1`.
#[derive(Debug, Clone, PartialEq)]
pub struct SupportStack {
    springs: Vec<SpringDamper>,
    masses: Vec<f64>,
}

impl SupportStack {
    /// A chain of `springs` and the lumped `masses` \[kg\] between them
    /// (`springs.len() == masses.len() + 1`, masses > 0, at most 8 layers).
    pub fn new(springs: Vec<SpringDamper>, masses: Vec<f64>) -> Result<Self, BeamError> {
        if springs.len() != masses.len() + 1 || springs.len() > 8 {
            return Err(BeamError::InvalidCount {
                name: "springs",
                value: springs.len(),
                reason: "a support chain needs one spring more than masses, and at most 8 springs",
            });
        }
        for s in &springs {
            SpringDamper::new(s.stiffness, s.damping)?;
        }
        for &m in &masses {
            positive("mass", m)?;
        }
        Ok(Self { springs, masses })
    }

    /// Direct fastening: the rail pad alone, on the foundation (ballastless track on a deck).
    pub fn direct(pad: SpringDamper) -> Result<Self, BeamError> {
        Self::new(vec![pad], vec![])
    }

    /// Pad → sleeper mass → ballast → foundation.
    pub fn ballasted(
        pad: SpringDamper,
        sleeper_mass: f64,
        ballast: SpringDamper,
    ) -> Result<Self, BeamError> {
        Self::new(vec![pad, ballast], vec![sleeper_mass])
    }

    /// Pad → sleeper → ballast → ballast mass → subgrade → foundation.
    pub fn ballasted_with_ballast_mass(
        pad: SpringDamper,
        sleeper_mass: f64,
        ballast: SpringDamper,
        ballast_mass: f64,
        subgrade: SpringDamper,
    ) -> Result<Self, BeamError> {
        Self::new(
            vec![pad, ballast, subgrade],
            vec![sleeper_mass, ballast_mass],
        )
    }

    /// Ballasted high-speed track of Zhai, Wang & Lin (2004), per rail seat, sleepers 0.6 m
    /// apart (references.md §D2.5): pad 6.5e7 N/m, 7.5e4 N s/m; half sleeper 125.5 kg; ballast
    /// 1.3775e8 N/m, 5.88e4 N s/m; ballast mass 531.4 kg; subgrade 7.75e7 N/m, 3.115e4 N s/m.
    /// The shear coupling between neighbouring ballast masses of the source is not modelled.
    pub fn ballasted_high_speed() -> Self {
        Self {
            springs: vec![
                SpringDamper {
                    stiffness: 6.5e7,
                    damping: 7.5e4,
                },
                SpringDamper {
                    stiffness: 1.3775e8,
                    damping: 5.88e4,
                },
                SpringDamper {
                    stiffness: 7.75e7,
                    damping: 3.115e4,
                },
            ],
            masses: vec![125.5, 531.4],
        }
    }

    /// Sleeper spacing of [`Self::ballasted_high_speed`] \[m\].
    pub const BALLASTED_HIGH_SPEED_SPACING: f64 = 0.6;

    /// Slab track per rail with fasteners `spacing` apart (references.md §D5.2, the CRTS-type slab
    /// track of Shock and Vibration 2014, 304219, Table 2): fastener 5.0e7 N/m and 3.625e4 N s/m;
    /// the slab (1.2e3 kg/m for both rails) lumped per fastener, 600 kg/m × spacing; the CA
    /// mortar layer 1.5e9 N/m² and 8.3e4 N s/m² per rail, times the spacing. The slab's own
    /// bending between fasteners is not modelled (a lumped slab).
    pub fn slab_track(spacing: f64) -> Result<Self, BeamError> {
        positive("sleeper_spacing", spacing)?;
        Self::new(
            vec![
                SpringDamper::new(5.0e7, 3.625e4)?,
                SpringDamper::new(1.5e9 * spacing, 8.3e4 * spacing)?,
            ],
            vec![600.0 * spacing],
        )
    }

    /// The springs from the rail down.
    pub fn springs(&self) -> &[SpringDamper] {
        &self.springs
    }

    /// The lumped masses from the rail down \[kg\].
    pub fn masses(&self) -> &[f64] {
        &self.masses
    }

    /// Static stiffness of the chain (springs in series) \[N/m\].
    pub fn static_stiffness(&self) -> f64 {
        1.0 / self.springs.iter().map(|s| 1.0 / s.stiffness).sum::<f64>()
    }

    /// The same chain with every stiffness multiplied by `k_factor` and every damping by
    /// `c_factor` (masses unchanged): stiff-track limits and parameter studies.
    pub fn scaled(&self, k_factor: f64, c_factor: f64) -> Result<Self, BeamError> {
        positive("k_factor", k_factor)?;
        non_negative("c_factor", c_factor)?;
        Self::new(
            self.springs
                .iter()
                .map(|s| SpringDamper {
                    stiffness: s.stiffness * k_factor,
                    damping: s.damping * c_factor,
                })
                .collect(),
            self.masses.clone(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Chains must have one spring more than masses; the series stiffness is 1/Σ(1/k).
    #[test]
    fn chain_rules_and_series_stiffness() {
        let pad = SpringDamper::new(2.0, 0.0).unwrap();
        assert!(SupportStack::new(vec![pad], vec![1.0]).is_err());
        assert!(SupportStack::new(vec![pad, pad], vec![-1.0]).is_err());
        assert!(SpringDamper::new(0.0, 1.0).is_err());
        let s = SupportStack::ballasted(pad, 3.0, SpringDamper::new(6.0, 0.0).unwrap()).unwrap();
        // 1/(1/2 + 1/6) = 1.5 exactly.
        assert!((s.static_stiffness() - 1.5).abs() < 1e-15);
        let z = SupportStack::ballasted_high_speed();
        assert_eq!(z.masses(), &[125.5, 531.4]);
        let slab = SupportStack::slab_track(0.6).unwrap();
        assert!((slab.masses()[0] - 360.0).abs() < 1e-9);
    }
}
