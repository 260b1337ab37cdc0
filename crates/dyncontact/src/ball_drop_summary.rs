//! Tests of the ball-drop summary as the CLI writes it (`sim::ball_drop_summary`).

#[cfg(test)]
mod tests {
    use sim::ball_drop_summary::summary;
    use sim::config::ScenarioConfig;

    /// A NaN or infinite result is written as `null` and listed under `non_finite`; a finite
    /// run lists nothing.
    #[test]
    fn non_finite_values_are_null_and_listed() {
        let text = include_str!("../../../examples/ball_drop_steel.toml");
        let options = sim::config::LoadOptions::default();
        let Ok(ScenarioConfig::BallDrop(p)) =
            sim::config::load(text, std::path::Path::new("."), &options)
        else {
            panic!("the example is a ball drop")
        };
        let mut r = p.scenario.simulate(false).unwrap();
        let clean = crate::output::json_text(&summary(&p, &r)).unwrap();
        assert!(!clean.contains("non_finite"), "{clean}");
        r.energy_drift = f64::NAN;
        r.impacts[0].peak_force = f64::INFINITY;
        let text = crate::output::json_text(&summary(&p, &r)).unwrap();
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert!(v["energy_drift"].is_null() && v["impacts"][0]["peak_force"].is_null());
        assert_eq!(
            v["non_finite"]["fields"],
            serde_json::json!(["energy_drift", "impacts[0].peak_force"])
        );
        assert!(!text.contains(": NaN") && !text.contains(": inf"));
    }
}
