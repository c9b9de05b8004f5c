//! Car files: the full-car parameters (METHOD.md section 7), validation and presets.
//!
//! A car is a JSON object; unknown keys are refused (a misspelt key is an error,
//! not a silently ignored field) and every message names the field at fault.

use crate::error::{Result, RideError};
use serde::{Deserialize, Serialize};

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
        let de = &mut serde_json::Deserializer::from_str(text);
        let car: Car = serde_path_to_error::deserialize(de).map_err(|e| {
            let path = e.path().to_string();
            let inner = e.into_inner();
            if path == "." || path == "?" || path.is_empty() {
                RideError::Json(inner.to_string())
            } else {
                RideError::field(path, inner.to_string())
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

    /// Checks every number: masses, inertias, lengths and stiffnesses > 0, tyre damping
    /// >= 0, suspension dampers > 0 (a zero damper leaves the RMS unbounded), all finite.
    pub fn validate(&self) -> Result<()> {
        let positive = [
            ("sprung_mass", self.sprung_mass),
            ("pitch_inertia", self.pitch_inertia),
            ("roll_inertia", self.roll_inertia),
            ("a", self.a),
            ("b", self.b),
            ("track_front", self.track_front),
            ("track_rear", self.track_rear),
        ];
        for (f, v) in positive {
            check_positive(f, v)?;
        }
        for (prefix, ax) in [("front", &self.front), ("rear", &self.rear)] {
            ax.validate(prefix)?;
        }
        Ok(())
    }

    /// The car with the front spring and damper replaced (the design variables).
    pub fn with_front(&self, ks: f64, cs: f64) -> Result<Car> {
        let mut c = self.clone();
        c.front.spring = ks;
        c.front.damper = cs;
        c.front.validate("front")?;
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
    /// Checks every field; messages name `prefix.field`.
    pub fn validate(&self, prefix: &str) -> Result<()> {
        check_positive(&format!("{prefix}.unsprung_mass"), self.unsprung_mass)?;
        check_positive(&format!("{prefix}.spring"), self.spring)?;
        check_positive(&format!("{prefix}.tire_stiffness"), self.tire_stiffness)?;
        check_damper(&format!("{prefix}.damper"), self.damper)?;
        let t = format!("{prefix}.tire_damping");
        check_finite(&t, self.tire_damping)?;
        if self.tire_damping < 0.0 {
            return Err(RideError::field(t, "must not be negative (N s/m)"));
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
    pub fn bounce_frequency(&self) -> f64 {
        crate::dos::bounce_frequency(self.ks, self.kt, self.ms)
    }

    /// Critical damping of the body on its spring, `2 sqrt(ks ms)`, N s/m.
    pub fn critical_damping(&self) -> f64 {
        2.0 * (self.ks * self.ms).sqrt()
    }
}

/// Checks a front design `(ks, cs)` as every evaluator takes it (same rules as a car
/// file's front axle): `ks` finite and > 0, `cs` finite and > 0 (with no suspension damping
/// the RMS is unbounded). Errors name `ks` or `cs`.
pub fn check_design(ks: f64, cs: f64) -> Result<()> {
    check_positive("ks", ks)?;
    check_damper("cs", cs)
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
