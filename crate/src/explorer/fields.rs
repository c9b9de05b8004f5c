//! Which page field an error belongs to: the core names fields by their paths in the
//! core's types (`front.spring`, `sws_limit`, `ks-range`, `damper.bump`, ...); the page
//! shows a message next to the input of a state field (`ks`, `swsLimit`, `box`, ...).

/// The state field a core field path belongs to: the design variables are the car's
/// front spring and damper; every other car-file field is the car's; the rest are
/// state fields already ("speed", "class", "tracks", "model", "nx", ...).
pub fn ui_field(core: &str) -> String {
    const CAR_FIELDS: [&str; 12] = [
        "car",
        "name",
        "source",
        "sprung_mass",
        "pitch_inertia",
        "roll_inertia",
        "a",
        "b",
        "track_front",
        "track_rear",
        "front",
        "rear",
    ];
    match core {
        "front.spring" | "ks" => "ks".into(),
        "front.damper" | "cs" => "cs".into(),
        "ks-range" | "cs-range" => "box".into(),
        "sws_limit" => "swsLimit".into(),
        "bounce_band" => "bounceBand".into(),
        "damping_band" => "dampingBand".into(),
        "dtl_margin" => "dtlMargin".into(),
        "approach" | "scheme" => "surrogate".into(),
        f if f.starts_with("damper.") => "damper".into(),
        f if f.starts_with("cases.") => "cases".into(),
        f if CAR_FIELDS.contains(&f)
            || f.starts_with("front.")
            || f.starts_with("rear.")
            || !f.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') =>
        {
            "car".into()
        }
        f => f.into(),
    }
}

#[cfg(test)]
mod tests {
    use super::ui_field;

    #[test]
    fn core_paths_map_to_page_fields() {
        for (core, page) in [
            ("front.spring", "ks"),
            ("ks", "ks"),
            ("front.damper", "cs"),
            ("cs-range", "box"),
            ("ks-range", "box"),
            ("sws_limit", "swsLimit"),
            ("cases.load_cases[1].mass", "cases"),
            ("cases", "cases"),
            ("case", "case"),
            ("bounce_band", "bounceBand"),
            ("damping_band", "dampingBand"),
            ("dtl_margin", "dtlMargin"),
            ("travel", "travel"),
            ("approach", "surrogate"),
            ("scheme", "surrogate"),
            ("damper.bump", "damper"),
            ("damper.knee.velocity", "damper"),
            ("sprung_mass", "car"),
            ("front.tire_stiffness", "car"),
            ("rear.spring", "car"),
            ("line 1 column 4", "car"),
            ("speed", "speed"),
            ("class", "class"),
            ("plan", "plan"),
            ("nx", "nx"),
        ] {
            assert_eq!(ui_field(core), page, "{core}");
        }
    }
}
