//! The Eurocode rules of a dynamic bridge check (references.md §T2, §T3): EN 1991-2 §6.4.6
//! (damping lower limits, Table 6.6; additional damping for vehicle–bridge interaction,
//! eq. 6.13; the modes to retain) and EN 1990 Annex A2 (deck acceleration and passenger
//! comfort limits). Ratios, not percent; SI units.

/// The bridge type of EN 1991-2 Table 6.6.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BridgeType {
    /// Steel and composite.
    SteelComposite,
    /// Prestressed concrete.
    PrestressedConcrete,
    /// Filler beam and reinforced concrete.
    ReinforcedConcrete,
}

impl BridgeType {
    /// The names accepted in a scenario file.
    pub const NAMES: &'static str =
        "steel, composite, prestressed_concrete, filler_beam, reinforced_concrete";

    /// `steel`/`composite`, `prestressed_concrete`, `filler_beam`/`reinforced_concrete`.
    pub fn by_name(name: &str) -> Option<Self> {
        match name.trim().to_ascii_lowercase().replace('-', "_").as_str() {
            "steel" | "composite" | "steel_composite" => Some(Self::SteelComposite),
            "prestressed_concrete" => Some(Self::PrestressedConcrete),
            "filler_beam" | "reinforced_concrete" => Some(Self::ReinforcedConcrete),
            _ => None,
        }
    }

    /// The lower limit of the damping ratio for a span `span` \[m\] (EN 1991-2 Table 6.6):
    /// steel/composite 0.5 % + 0.125 (20 − L) % for L < 20 m, else 0.5 %; prestressed
    /// concrete 1.0 % + 0.07 (20 − L) %; filler beam and reinforced concrete
    /// 1.5 % + 0.07 (20 − L) %.
    pub fn damping_lower_limit(self, span: f64) -> f64 {
        let short = (20.0 - span).max(0.0);
        let percent = match self {
            Self::SteelComposite => 0.5 + 0.125 * short,
            Self::PrestressedConcrete => 1.0 + 0.07 * short,
            Self::ReinforcedConcrete => 1.5 + 0.07 * short,
        };
        percent / 100.0
    }
}

/// The additional damping Δζ of vehicle–bridge interaction for spans L < 30 m (EN 1991-2
/// eq. 6.13): Δζ = (0.0187 L − 0.00064 L²) / (1 − 0.0441 L − 0.0044 L² + 0.000255 L³) %;
/// 0 from 30 m. The numerator changes sign at L = 0.0187/0.00064 = 29.2 m, so the formula's
/// slightly negative values for 29.2 ≤ L < 30 m are taken as 0 (an additional damping never
/// reduces the damping).
pub fn additional_damping(span: f64) -> f64 {
    if span >= 30.0 || span <= 0.0 {
        return 0.0;
    }
    let l = span;
    let percent =
        (0.0187 * l - 0.00064 * l * l) / (1.0 - 0.0441 * l - 0.0044 * l * l + 0.000255 * l * l * l);
    (percent / 100.0).max(0.0)
}

/// The damping ratio of a dynamic check: the lower limit plus Δζ.
pub fn damping_ratio(bridge: BridgeType, span: f64) -> f64 {
    bridge.damping_lower_limit(span) + additional_damping(span)
}

/// The highest frequency whose modes a dynamic analysis retains (EN 1991-2 §6.4.6.5(2) with
/// EN 1990 A2.4.4.2.1): max(30 Hz, 1.5 n₀, n₃), n₀ the first and n₃ the third bending
/// frequency \[Hz\].
pub fn mode_frequency_limit(n0: f64, n3: f64) -> f64 {
    30.0f64.max(1.5 * n0).max(n3)
}

/// The track on the deck, for the deck acceleration limit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Track {
    /// Ballasted track: 3.5 m/s² (EN 1990 A2.4.4.2.1).
    Ballasted,
    /// Direct-fastened (ballastless) track: 5.0 m/s².
    Ballastless,
}

impl Track {
    /// `ballasted` or `ballastless` (also `direct_fastened`).
    pub fn by_name(name: &str) -> Option<Self> {
        match name.trim().to_ascii_lowercase().replace('-', "_").as_str() {
            "ballasted" => Some(Self::Ballasted),
            "ballastless" | "direct_fastened" => Some(Self::Ballastless),
            _ => None,
        }
    }

    /// The scenario-file name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Ballasted => "ballasted",
            Self::Ballastless => "ballastless",
        }
    }

    /// The peak deck acceleration limit \[m/s²\].
    pub fn acceleration_limit(self) -> f64 {
        match self {
            Self::Ballasted => 3.5,
            Self::Ballastless => 5.0,
        }
    }
}

/// The passenger comfort levels of EN 1990 A2.4.4.3.2 (Table A2.9): the maximum vertical
/// acceleration inside the coach b_v \[m/s²\] of "very good", "good" and "acceptable".
pub const COMFORT_LEVELS: [(&str, f64); 3] =
    [("very good", 1.0), ("good", 1.3), ("acceptable", 2.0)];

/// The comfort level reached by a peak vertical body acceleration \[m/s²\] (`None`: worse than
/// acceptable).
pub fn comfort_level(body_acceleration: f64) -> Option<&'static str> {
    COMFORT_LEVELS
        .iter()
        .find(|(_, limit)| body_acceleration <= *limit)
        .map(|(name, _)| *name)
}

/// The resonance speeds v_i = n₀ D / i \[m/s\] (i = 1, 2, …) of a train with regular
/// spacing D \[m\] on a bridge of first frequency n₀ \[Hz\] (EN 1991-2 §6.4.4), those in
/// [v_min, v_max].
pub fn resonance_speeds(n0: f64, spacing: f64, v_min: f64, v_max: f64) -> Vec<(usize, f64)> {
    (1..=20)
        .map(|i| (i, n0 * spacing / i as f64))
        .filter(|&(_, v)| v >= v_min && v <= v_max)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn damping_follows_table_6_6_and_eq_6_13() {
        // Table 6.6 by hand: L = 10 m steel 0.5 + 1.25 = 1.75 %, prestressed 1.7 %, RC 2.2 %;
        // L ≥ 20 m the constants.
        assert!((BridgeType::SteelComposite.damping_lower_limit(10.0) - 0.0175).abs() < 1e-15);
        assert!((BridgeType::PrestressedConcrete.damping_lower_limit(10.0) - 0.017).abs() < 1e-15);
        assert!((BridgeType::ReinforcedConcrete.damping_lower_limit(10.0) - 0.022).abs() < 1e-15);
        assert_eq!(
            BridgeType::ReinforcedConcrete.damping_lower_limit(25.0),
            0.015
        );
        // eq. 6.13 at L = 10 m: (0.187 − 0.064)/(1 − 0.441 − 0.44 + 0.255) = 0.123/0.374 %.
        assert!((additional_damping(10.0) - 0.123 / 0.374 / 100.0).abs() < 1e-15);
        assert_eq!(additional_damping(30.0), 0.0);
        assert!(additional_damping(29.0) > 0.0);
        assert_eq!(additional_damping(29.9), 0.0);
        assert_eq!(
            BridgeType::by_name("filler_beam"),
            Some(BridgeType::ReinforcedConcrete)
        );
        assert_eq!(BridgeType::by_name("wood"), None);
    }

    #[test]
    fn limits_modes_comfort_and_resonance() {
        assert_eq!(mode_frequency_limit(5.0, 45.0), 45.0);
        assert_eq!(mode_frequency_limit(5.0, 20.0), 30.0);
        assert_eq!(mode_frequency_limit(25.0, 31.0), 37.5);
        assert_eq!(Track::Ballasted.acceleration_limit(), 3.5);
        assert_eq!(
            Track::by_name("ballastless").unwrap().acceleration_limit(),
            5.0
        );
        assert_eq!(comfort_level(0.9), Some("very good"));
        assert_eq!(comfort_level(1.2), Some("good"));
        assert_eq!(comfort_level(2.5), None);
        let v = resonance_speeds(5.0, 18.0, 38.0, 117.0);
        assert_eq!(v, vec![(1, 90.0), (2, 45.0)]);
    }
}
