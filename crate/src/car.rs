//! Car files: the full-car parameters (METHOD.md section 7), validation and presets.
//!
//! A car is a JSON object; unknown keys are refused (a misspelt key is an error,
//! not a silently ignored field) and every message names the field at fault.

use crate::error::{Result, RideError};
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// One axle's corner: unsprung mass, suspension and tyre (identical left and right).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Axle {
    /// Unsprung mass of one corner, kg.
    pub unsprung_mass: f64,
    /// Suspension spring rate at the wheel, N/m.
    pub spring: f64,
    /// Suspension damper rate at the wheel, N s/m.
    pub damper: f64,
    /// Tyre vertical stiffness, N/m.
    pub tire_stiffness: f64,
    /// Tyre vertical damping, N s/m (usually 0).
    #[serde(default)]
    pub tire_damping: f64,
}

/// A full car: rigid body with heave, pitch and roll on four corners.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Car {
    /// Display name.
    pub name: String,
    /// Literature source of the values.
    #[serde(default)]
    pub source: String,
    /// Sprung (body) mass M, kg.
    pub sprung_mass: f64,
    /// Pitch moment of inertia Iyy about the centre of gravity, kg m^2.
    pub pitch_inertia: f64,
    /// Roll moment of inertia Ixx about the centre of gravity, kg m^2.
    pub roll_inertia: f64,
    /// Distance from the centre of gravity forward to the front axle, m.
    pub a: f64,
    /// Distance from the centre of gravity back to the rear axle, m.
    pub b: f64,
    /// Front track width, m.
    pub track_front: f64,
    /// Rear track width, m.
    pub track_rear: f64,
    /// Front corners.
    pub front: Axle,
    /// Rear corners.
    pub rear: Axle,
}

/// The quarter car of the front corner (LoFi), derived from a full car.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct QuarterCar {
    /// Sprung mass `ms = M b / (2 L)`, kg.
    pub ms: f64,
    /// Unsprung mass, kg.
    pub mu: f64,
    /// Suspension spring rate, N/m.
    pub ks: f64,
    /// Suspension damper rate, N s/m.
    pub cs: f64,
    /// Tyre stiffness, N/m.
    pub kt: f64,
    /// Tyre damping, N s/m.
    pub ct: f64,
}

/// The shipped presets: `(file stem, JSON text)`. The first is the default datum car.
pub const PRESETS: [(&str, &str); 3] = [
    ("sedan", include_str!("../../assets/cars/sedan.json")),
    ("compact", include_str!("../../assets/cars/compact.json")),
    ("suv", include_str!("../../assets/cars/suv.json")),
];

impl Car {
    /// Parses and validates a car from JSON text.
    pub fn from_json(text: &str) -> Result<Car> {
        check_object("car", "a car file", text)?;
        let car: Car = crate::json_path::from_str(text).map_err(|(path, e)| {
            let inner = e.to_string();
            // A car file may also list `load_cases` (robust::CarFile reads them).
            let inner = match inner.split_once(", expected one of ") {
                Some((head, keys)) if head.starts_with("unknown field") => {
                    format!("{head}, expected one of {keys}, `load_cases`")
                }
                _ => inner,
            };
            if path.is_empty() {
                RideError::Json(inner)
            } else {
                RideError::field(path, inner)
            }
        })?;
        car.validate()?;
        Ok(car)
    }

    /// The car as pretty JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default()
    }

    /// A shipped preset by name ("sedan", "compact", "suv").
    pub fn preset(name: &str) -> Result<Car> {
        let (_, text) = PRESETS.iter().find(|(n, _)| *n == name).ok_or_else(|| {
            RideError::field(
                "car",
                format!("no preset named '{name}' (sedan, compact, suv)"),
            )
        })?;
        Car::from_json(text)
    }

    /// The default datum car (Ikenaga et al. 2000 set, METHOD.md section 7).
    pub fn datum() -> Car {
        // The preset is compiled in and covered by tests; parsing cannot fail at run time.
        Car::from_json(PRESETS[0].1).expect("shipped datum preset is valid")
    }

    /// Wheelbase `L = a + b`, m.
    pub fn wheelbase(&self) -> f64 {
        self.a + self.b
    }

    /// Checks every number against its physical range ([`crate::domain`]): masses,
    /// lengths, rates, and the inertias through the body's dynamic index
    /// `Iyy / (M a b)` and roll index `Ixx / (M (t/2)^2)`, so a body whose mass and
    /// inertias do not belong together (a 1e9 kg body with a car's inertia) is refused.
    pub fn validate(&self) -> Result<()> {
        use crate::domain::{AXLE_DISTANCE, DYNAMIC_INDEX, ROLL_INDEX, SPRUNG_MASS, TRACK};
        for (f, v, limit) in [
            ("sprung_mass", self.sprung_mass, &SPRUNG_MASS),
            ("a", self.a, &AXLE_DISTANCE),
            ("b", self.b, &AXLE_DISTANCE),
            ("track_front", self.track_front, &TRACK),
            ("track_rear", self.track_rear, &TRACK),
        ] {
            check_positive(f, v)?;
            limit.check(f, v)?;
        }
        let m_ab = self.sprung_mass * self.a * self.b;
        check_inertia("pitch_inertia", self.pitch_inertia, m_ab, &DYNAMIC_INDEX)?;
        let half_track = (self.track_front + self.track_rear) / 4.0;
        let m_t2 = self.sprung_mass * half_track * half_track;
        check_inertia("roll_inertia", self.roll_inertia, m_t2, &ROLL_INDEX)?;
        let l = self.wheelbase();
        let shares = [
            ("front", &self.front, self.sprung_mass * self.b / (2.0 * l)),
            ("rear", &self.rear, self.sprung_mass * self.a / (2.0 * l)),
        ];
        for (prefix, ax, _) in shares {
            ax.validate(prefix)?;
        }
        for (prefix, ax, ms) in shares {
            ax.validate_corner(prefix, ms)?;
        }
        Ok(())
    }

    /// The domain of the front design `(ks, cs)` on this car ([`DesignDomain`]).
    pub fn design_domain(&self) -> DesignDomain {
        let q = self.quarter();
        DesignDomain::new(q.ms, q.kt)
    }

    /// The car with the front spring and damper replaced (the design variables).
    pub fn with_front(&self, ks: f64, cs: f64) -> Result<Car> {
        let mut c = self.clone();
        c.front.spring = ks;
        c.front.damper = cs;
        c.front.validate("front")?;
        self.design_domain().check(ks, cs)?;
        Ok(c)
    }

    /// The front-corner quarter car: `ms = M b / (2 L)` (static share of one front corner).
    pub fn quarter(&self) -> QuarterCar {
        QuarterCar {
            ms: self.sprung_mass * self.b / (2.0 * self.wheelbase()),
            mu: self.front.unsprung_mass,
            ks: self.front.spring,
            cs: self.front.damper,
            kt: self.front.tire_stiffness,
            ct: self.front.tire_damping,
        }
    }

    /// Static load on one front wheel `(M b / (2 L) + mu_f) g`, N.
    pub fn front_wheel_load(&self) -> f64 {
        let q = self.quarter();
        (q.ms + q.mu) * 9.80665
    }
}

impl Axle {
    /// Checks every field against its physical range; messages name `prefix.field`.
    pub fn validate(&self, prefix: &str) -> Result<()> {
        use crate::domain::{DAMPER, SPRING, TIRE_DAMPING, TIRE_STIFFNESS, UNSPRUNG_MASS};
        // An axle inside every range passes without writing a field name (a map checks
        // one at every point); the checks below name the first fault.
        let inside = [
            (self.unsprung_mass, &UNSPRUNG_MASS),
            (self.spring, &SPRING),
            (self.tire_stiffness, &TIRE_STIFFNESS),
            (self.damper, &DAMPER),
        ]
        .iter()
        .all(|(v, limit)| *v > 0.0 && limit.contains(*v))
            && self.tire_damping >= 0.0
            && TIRE_DAMPING.contains(self.tire_damping);
        if inside {
            return Ok(());
        }
        for (f, v, limit) in [
            ("unsprung_mass", self.unsprung_mass, &UNSPRUNG_MASS),
            ("spring", self.spring, &SPRING),
            ("tire_stiffness", self.tire_stiffness, &TIRE_STIFFNESS),
        ] {
            let field = format!("{prefix}.{f}");
            check_positive(&field, v)?;
            limit.check(&field, v)?;
        }
        check_damper(&format!("{prefix}.damper"), self.damper)?;
        let t = format!("{prefix}.tire_damping");
        check_finite(&t, self.tire_damping)?;
        if self.tire_damping < 0.0 {
            return Err(RideError::field(t, "must not be negative (N s/m)"));
        }
        TIRE_DAMPING.check(&t, self.tire_damping)?;
        // The damper's own range (after the sign and zero messages above).
        DAMPER.check(&format!("{prefix}.damper"), self.damper)
    }
}

impl Axle {
    /// Checks the corner as a whole on its share `ms` (kg) of the body: the mass ratio,
    /// the wheel-hop and body-bounce frequencies and the damping ratio
    /// ([`crate::domain`]'s derived limits); messages name `prefix.field` and give the
    /// range of that field for this corner.
    fn validate_corner(&self, prefix: &str, ms: f64) -> Result<()> {
        use crate::domain::{num, MASS_RATIO, WHEEL_HOP};
        let field = |f: &str| format!("{prefix}.{f}");
        let ratio = self.unsprung_mass / ms;
        if !MASS_RATIO.contains(ratio) {
            return Err(RideError::field(
                field("unsprung_mass"),
                format!(
                    "{} kg on the corner's {} kg share of the body is a mass ratio of {}, outside {}..{} ({}): for this corner {}..{} kg",
                    num(self.unsprung_mass),
                    num(ms),
                    num(ratio),
                    num(MASS_RATIO.min),
                    num(MASS_RATIO.max),
                    MASS_RATIO.why,
                    num(MASS_RATIO.min * ms),
                    num(MASS_RATIO.max * ms)
                ),
            ));
        }
        let hop = ((self.spring + self.tire_stiffness) / self.unsprung_mass).sqrt() / TAU;
        if !WHEEL_HOP.contains(hop) {
            let w = |f: f64| (TAU * f).powi(2) * self.unsprung_mass - self.spring;
            return Err(RideError::field(
                field("tire_stiffness"),
                format!(
                    "{} N/m under a {} kg wheel gives a wheel-hop frequency of {} Hz, outside {}..{} Hz ({}): for this wheel {}..{} N/m",
                    num(self.tire_stiffness),
                    num(self.unsprung_mass),
                    num(hop),
                    num(WHEEL_HOP.min),
                    num(WHEEL_HOP.max),
                    WHEEL_HOP.why,
                    num(w(WHEEL_HOP.min).max(0.0)),
                    num(w(WHEEL_HOP.max))
                ),
            ));
        }
        DesignDomain::new(ms, self.tire_stiffness).check_named(
            self.spring,
            self.damper,
            &field("spring"),
            &field("damper"),
        )
    }
}

/// Where a corner's spring and damper may lie for its share `ms` (kg) of the body and its
/// tyre rate `kt` (N/m): each in its own range ([`crate::domain::SPRING`],
/// [`crate::domain::DAMPER`]), the body-bounce frequency on the ride rate in
/// [`crate::domain::BOUNCE`]'s and the damping ratio in [`crate::domain::DAMPING_RATIO`]'s.
/// The bounce range is a spring range (the ride rate `Kw = k kt / (k + kt)` grows with
/// `k`), precomputed so a map's cell needs four comparisons and a square root.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DesignDomain {
    ms: f64,
    kt: f64,
    /// Springs with the bounce frequency in range, N/m (`ks_hi` may be infinite).
    ks_lo: f64,
    ks_hi: f64,
}

impl DesignDomain {
    /// The domain of a corner with body share `ms` (kg) on a tyre of rate `kt` (N/m).
    pub fn new(ms: f64, kt: f64) -> DesignDomain {
        use crate::domain::BOUNCE;
        // Kw = ms (2 pi f)^2; k = Kw kt / (kt - Kw) while Kw < kt.
        let spring = |f: f64| {
            let kw = ms * (TAU * f).powi(2);
            if kw < kt {
                kw * kt / (kt - kw)
            } else {
                f64::INFINITY
            }
        };
        DesignDomain {
            ms,
            kt,
            ks_lo: spring(BOUNCE.min),
            ks_hi: spring(BOUNCE.max),
        }
    }

    /// True when `(ks, cs)` lies in the domain.
    pub fn contains(&self, ks: f64, cs: f64) -> bool {
        use crate::domain::DAMPING_RATIO;
        design_in_domain(ks, cs) && ks >= self.ks_lo && ks <= self.ks_hi && {
            let zeta = cs / (2.0 * (ks * self.ms).sqrt());
            DAMPING_RATIO.contains(zeta)
        }
    }

    /// Checks a front design; errors name `ks` or `cs`.
    pub fn check(&self, ks: f64, cs: f64) -> Result<()> {
        if self.contains(ks, cs) {
            return Ok(());
        }
        check_design(ks, cs)?;
        self.check_named(ks, cs, "ks", "cs")
    }

    /// Checks a spring `k` and damper `c` against the derived limits; errors name
    /// `spring_field` or `damper_field` with the range of that field on this corner.
    fn check_named(&self, k: f64, c: f64, spring_field: &str, damper_field: &str) -> Result<()> {
        use crate::domain::{num, BOUNCE, DAMPING_RATIO};
        let f = bounce_frequency(k, self.kt, self.ms);
        if !BOUNCE.contains(f) {
            return Err(RideError::field(
                spring_field,
                format!(
                    "{} N/m gives a body-bounce frequency of {} Hz on this corner's {} kg share of the body, outside {}..{} Hz ({}): for this corner {}..{} N/m",
                    num(k),
                    num(f),
                    num(self.ms),
                    num(BOUNCE.min),
                    num(BOUNCE.max),
                    BOUNCE.why,
                    num(self.ks_lo),
                    num(self.ks_hi)
                ),
            ));
        }
        let zeta = damping_ratio(k, c, self.ms);
        if !DAMPING_RATIO.contains(zeta) {
            let c_of = |z: f64| 2.0 * z * (k * self.ms).sqrt();
            return Err(RideError::field(
                damper_field,
                format!(
                    "{} N s/m gives a body damping ratio of {} with a {} N/m spring on this corner's {} kg share of the body, outside {}..{} ({}): with this spring {}..{} N s/m",
                    num(c),
                    num(zeta),
                    num(k),
                    num(self.ms),
                    num(DAMPING_RATIO.min),
                    num(DAMPING_RATIO.max),
                    DAMPING_RATIO.why,
                    num(c_of(DAMPING_RATIO.min)),
                    num(c_of(DAMPING_RATIO.max))
                ),
            ));
        }
        Ok(())
    }
}

impl QuarterCar {
    /// Checks every parameter (same rules as a car file).
    pub fn validate(&self) -> Result<()> {
        for (f, v) in [
            ("ms", self.ms),
            ("mu", self.mu),
            ("ks", self.ks),
            ("kt", self.kt),
        ] {
            check_positive(f, v)?;
        }
        check_finite("cs", self.cs)?;
        if self.cs <= 0.0 {
            return Err(RideError::field(
                "cs",
                "must be > 0: with no suspension damping the RMS response to a white road velocity is unbounded",
            ));
        }
        check_finite("ct", self.ct)?;
        if self.ct < 0.0 {
            return Err(RideError::field("ct", "must not be negative (N s/m)"));
        }
        Ok(())
    }

    /// Wheel (ride) rate `Kw = ks kt / (ks + kt)`, N/m.
    pub fn wheel_rate(&self) -> f64 {
        self.ks * self.kt / (self.ks + self.kt)
    }

    /// Body-bounce frequency `sqrt(Kw / ms) / (2 pi)`, Hz.
    pub(crate) fn bounce_frequency(&self) -> f64 {
        bounce_frequency(self.ks, self.kt, self.ms)
    }

    /// Critical damping of the body on its spring, `2 sqrt(ks ms)`, N s/m.
    pub fn critical_damping(&self) -> f64 {
        2.0 * (self.ks * self.ms).sqrt()
    }
}

/// Refuses text that is not one JSON object before serde reads it, so an empty file or
/// an array is named as such (`what` says which file, `field` names it) rather than
/// "EOF while parsing" or "invalid type: sequence".
pub(crate) fn check_object(field: &str, what: &str, text: &str) -> Result<()> {
    let kind = match text.trim_start().chars().next() {
        None => {
            return Err(RideError::field(
                field,
                format!("the file is empty: {what} is one JSON object {{\"key\": value, ...}}"),
            ))
        }
        Some('[') => "an array",
        Some('"') => "a string",
        Some(c) if c == '-' || c.is_ascii_digit() => "a number",
        // An object, or text that is not JSON at all: serde says where it breaks.
        _ => return Ok(()),
    };
    Err(RideError::field(
        field,
        format!("{what} is one JSON object {{\"key\": value, ...}}; this text is {kind}"),
    ))
}

/// Checks a front design `(ks, cs)` as every evaluator takes it (same rules as a car
/// file's front axle): `ks` in [`crate::domain::SPRING`]'s range, `cs` finite and > 0 (with
/// no suspension damping the RMS is unbounded) and in [`crate::domain::DAMPER`]'s. Errors
/// name `ks` or `cs`.
pub(crate) fn check_design(ks: f64, cs: f64) -> Result<()> {
    check_positive("ks", ks)?;
    crate::domain::SPRING.check("ks", ks)?;
    check_damper("cs", cs)?;
    crate::domain::DAMPER.check("cs", cs)
}

/// True when `(ks, cs)` lies in the design domain: the few comparisons a map's cell
/// needs before [`check_design`] formats a message.
pub(crate) fn design_in_domain(ks: f64, cs: f64) -> bool {
    crate::domain::SPRING.contains(ks) && crate::domain::DAMPER.contains(cs)
}

/// An inertia `i` checked through its index `i / scale` (kg m^2 over kg m^2); the
/// message states the index, its range and the inertias that range allows.
fn check_inertia(field: &str, i: f64, scale: f64, index: &crate::domain::Limit) -> Result<()> {
    check_positive(field, i)?;
    if index.contains(i / scale) {
        return Ok(());
    }
    use crate::domain::num;
    Err(RideError::field(
        field,
        format!(
            "{} kg m^2 gives a {} of {}, outside {}..{} ({}): for this body {}..{} kg m^2",
            num(i),
            index.what,
            num(i / scale),
            num(index.min),
            num(index.max),
            index.why,
            num(index.min * scale),
            num(index.max * scale)
        ),
    ))
}

/// A suspension damper rate: finite, not negative, not zero (unbounded RMS).
fn check_damper(field: &str, v: f64) -> Result<()> {
    check_finite(field, v)?;
    if v < 0.0 {
        return Err(RideError::field(field, "must not be negative (N s/m)"));
    }
    if v == 0.0 {
        return Err(RideError::field(
            field,
            "must be > 0: with no suspension damping the RMS response to a white road velocity is unbounded",
        ));
    }
    Ok(())
}

fn check_finite(field: &str, v: f64) -> Result<()> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(RideError::field(field, "must be a finite number"))
    }
}

fn check_positive(field: &str, v: f64) -> Result<()> {
    check_finite(field, v)?;
    if v > 0.0 {
        Ok(())
    } else {
        Err(RideError::field(field, format!("must be > 0 (got {v})")))
    }
}

/// Body-bounce frequency of the quarter car on its ride rate, Hz:
/// `f = sqrt(Kw / ms) / (2 pi)`, `Kw = ks kt / (ks + kt)`.
pub(crate) fn bounce_frequency(ks: f64, kt: f64, ms: f64) -> f64 {
    let kw = ks * kt / (ks + kt);
    (kw / ms).sqrt() / (2.0 * std::f64::consts::PI)
}

/// Body damping ratio `zeta = cs / (2 sqrt(ks ms))` (Gillespie's ride definition), -.
pub fn damping_ratio(ks: f64, cs: f64, ms: f64) -> f64 {
    cs / (2.0 * (ks * ms).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_parse_and_datum_matches_method() {
        for (name, _) in PRESETS {
            let c = Car::preset(name).unwrap();
            assert!(!c.source.is_empty(), "{name} has no source");
        }
        let d = Car::datum();
        assert_eq!(d.sprung_mass, 1460.0);
        assert_eq!(d.front.spring, 19960.0);
        // ms = 1460 * 1.803 / (2 * 2.814) = 467.729 211 kg
        assert!((d.quarter().ms - 467.729_211).abs() < 1e-5);
    }

    fn datum_value() -> serde_json::Value {
        serde_json::from_str(PRESETS[0].1).unwrap()
    }

    fn err_of(v: serde_json::Value) -> String {
        Car::from_json(&v.to_string()).unwrap_err().to_string()
    }

    #[test]
    fn every_bad_input_class_names_its_field() {
        let mut v = datum_value();
        v.as_object_mut().unwrap().remove("pitch_inertia");
        assert!(err_of(v).contains("pitch_inertia"));

        let mut v = datum_value();
        v["front"].as_object_mut().unwrap().remove("spring");
        let e = err_of(v);
        assert!(e.starts_with("front") && e.contains("spring"), "{e}");

        let mut v = datum_value();
        let x = v.as_object_mut().unwrap().remove("a").unwrap();
        v["aa"] = x;
        let e = err_of(v);
        assert!(e.contains("aa"), "{e}");

        let mut v = datum_value();
        v["sprung_mass"] = serde_json::json!(-3.0);
        assert!(err_of(v).starts_with("sprung_mass: must be > 0"));

        let mut v = datum_value();
        v["rear"]["tire_stiffness"] = serde_json::json!(0.0);
        assert!(err_of(v).starts_with("rear.tire_stiffness"));

        let mut v = datum_value();
        v["track_front"] = serde_json::json!(0.0);
        assert!(err_of(v).starts_with("track_front"));

        let mut v = datum_value();
        v["front"]["damper"] = serde_json::json!(-10.0);
        assert!(err_of(v).starts_with("front.damper: must not be negative"));

        let mut v = datum_value();
        v["front"]["damper"] = serde_json::json!(0.0);
        assert!(err_of(v).contains("unbounded"));

        let mut v = datum_value();
        v["rear"]["tire_damping"] = serde_json::json!(-1.0);
        assert!(err_of(v).starts_with("rear.tire_damping"));

        let mut v = datum_value();
        v["a"] = serde_json::json!("one");
        assert!(err_of(v).starts_with("a:"));

        // Infinite and NaN values cannot be written in JSON; 1e999 overflows and is refused.
        let text = PRESETS[0]
            .1
            .replace("\"sprung_mass\": 1460", "\"sprung_mass\": 1e999");
        assert!(Car::from_json(&text)
            .unwrap_err()
            .to_string()
            .contains("sprung_mass"));
        let q = QuarterCar {
            ms: f64::NAN,
            ..Car::datum().quarter()
        };
        assert!(q.validate().unwrap_err().to_string().starts_with("ms"));
        assert!(Car::datum()
            .with_front(f64::INFINITY, 1000.0)
            .unwrap_err()
            .to_string()
            .starts_with("front.spring"));

        assert!(matches!(
            Car::from_json("{not json"),
            Err(RideError::Json(_)) | Err(RideError::Field { .. })
        ));
    }
}
