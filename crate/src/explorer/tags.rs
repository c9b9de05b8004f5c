//! What the page's results are tagged with (issue #28): four numbers the session gives for
//! its state, each a hash of the state fields one kind of result depends on. The page
//! keeps a result with the tag it was asked under and shows it while the session's tag
//! is the same, so it neither knows which fields a result depends on nor builds keys of
//! its own. Tags are of content, not counters: the page's three sessions (main thread,
//! HiFi worker, heavy worker), and the first-screen and on-demand modules, give equal
//! tags for equal states, so a worker's answer is compared with the main thread's tag.

use super::state::{State, FIT_FIELDS, REPORT_FIELDS, STATE_FIELDS};
use serde::Serialize;
use std::hash::{DefaultHasher, Hash, Hasher};

/// A session's tags: each a 53-bit hash (a whole number a JS number holds exactly).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Tags {
    /// The design's reports: the fields of [`REPORT_FIELDS`] (car, design point, road).
    pub design: f64,
    /// The datum's reports: the same fields with the design at the car's own front.
    pub datum: f64,
    /// The surrogate's fit and the maps' values: the fields of [`FIT_FIELDS`].
    pub fit: f64,
    /// Everything but the design point (Ks, Cs): maps with their masks, fronts, the
    /// adaptive run.
    pub scenario: f64,
}

impl Tags {
    /// The tags of `state`, whose car's own front is spring `datum.0` N/m and damper
    /// `datum.1` N s/m.
    pub fn of(state: &State, datum: (f64, f64)) -> Tags {
        let design = (state.ks, state.cs);
        let scenario = STATE_FIELDS.iter().filter(|f| !matches!(**f, "ks" | "cs"));
        Tags {
            design: tag(state, REPORT_FIELDS.iter(), design),
            datum: tag(state, REPORT_FIELDS.iter(), datum),
            fit: tag(state, FIT_FIELDS.iter(), design),
            scenario: tag(state, scenario, design),
        }
    }
}

/// The hash of `fields` of `state` (names and values), the design point `(ks, cs)` in
/// place of the state's, as a whole number below 2^53.
fn tag<'a>(state: &State, fields: impl Iterator<Item = &'a &'a str>, design: (f64, f64)) -> f64 {
    // std's SipHash with its fixed keys: the same in every module of one build, which is
    // all the page compares (a tag is never stored or sent elsewhere).
    let mut h = DefaultHasher::new();
    for field in fields {
        field.hash(&mut h);
        hash_field(state, field, design, &mut h);
    }
    (h.finish() >> 11) as f64
}

/// Feeds the value of the state field `field` (a JS name of [`STATE_FIELDS`]) to `h`;
/// numbers by their bits.
fn hash_field(s: &State, field: &str, design: (f64, f64), h: &mut DefaultHasher) {
    let bits = |x: &Option<f64>| x.map(f64::to_bits);
    let pair = |x: &Option<[f64; 2]>| x.map(|p| p.map(f64::to_bits));
    match field {
        "car" => s.car.hash(h),
        "carJson" => s.car_json.hash(h),
        "ks" => design.0.to_bits().hash(h),
        "cs" => design.1.to_bits().hash(h),
        "class" => s.class.hash(h),
        "roadProfile" => s.road_profile.hash(h),
        "speed" => s.speed.to_bits().hash(h),
        "tracks" => s.tracks.hash(h),
        "ksMin" => bits(&s.ks_min).hash(h),
        "ksMax" => bits(&s.ks_max).hash(h),
        "csMin" => bits(&s.cs_min).hash(h),
        "csMax" => bits(&s.cs_max).hash(h),
        "swsLimit" => bits(&s.sws_limit).hash(h),
        "bounceBand" => pair(&s.bounce_band).hash(h),
        "dampingBand" => pair(&s.damping_band).hash(h),
        "noWorse" => s.no_worse.hash(h),
        "dtlMargin" => bits(&s.dtl_margin).hash(h),
        "travel" => pair(&s.travel).hash(h),
        "surrogate" => s.surrogate.hash(h),
        "plan" => s.plan.hash(h),
        "comfort" => s.comfort.hash(h),
        "pick" => s.pick.hash(h),
        "cases" => s.cases.hash(h),
        "case" => s.case.hash(h),
        // Every name of STATE_FIELDS is above (tested: each changes its tags).
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each state field changed alone changes exactly the tags whose results depend on
    /// it: `fit` for FIT_FIELDS, `design` for REPORT_FIELDS, `datum` for REPORT_FIELDS
    /// but the design point, `scenario` for every field but the design point.
    #[test]
    fn each_field_changes_exactly_the_tags_that_depend_on_it() {
        let mut others = crate::explorer::tests::other_values();
        others.extend([
            ("carJson", "{}".into()),
            ("roadProfile", "road.csv#0".into()),
            ("case", "1".into()),
        ]);
        let base = State::default();
        let datum = (base.ks, base.cs);
        let t0 = Tags::of(&base, datum);
        let mut seen = Vec::new();
        for (field, value) in others {
            let mut v = serde_json::to_value(&base).unwrap();
            v[field] = value;
            let state: State = serde_json::from_value(v).unwrap();
            let t = Tags::of(&state, datum);
            let design = matches!(field, "ks" | "cs");
            assert_eq!(t.fit != t0.fit, FIT_FIELDS.contains(&field), "{field}: fit");
            assert_eq!(
                t.design != t0.design,
                REPORT_FIELDS.contains(&field),
                "{field}: design"
            );
            assert_eq!(
                t.datum != t0.datum,
                REPORT_FIELDS.contains(&field) && !design,
                "{field}: datum"
            );
            assert_eq!(t.scenario != t0.scenario, !design, "{field}: scenario");
            seen.push(field);
        }
        seen.sort_unstable();
        let mut all = STATE_FIELDS.to_vec();
        all.sort_unstable();
        assert_eq!(seen, all, "every state field is tried");
    }

    /// The datum tag is the design tag of the state moved to the datum, and every tag is
    /// a whole number a JS number holds exactly.
    #[test]
    fn the_datum_tag_is_the_design_tag_at_the_datum() {
        let s = State {
            ks: 30_000.0,
            cs: 2_000.0,
            ..State::default()
        };
        let datum = State::default();
        let t = Tags::of(&s, (datum.ks, datum.cs));
        assert_eq!(t.datum, Tags::of(&datum, (datum.ks, datum.cs)).design);
        assert_ne!(t.datum, t.design);
        for x in [t.design, t.datum, t.fit, t.scenario] {
            assert!(x >= 0.0 && x < 2f64.powi(53) && x.fract() == 0.0, "{x}");
        }
    }
}
