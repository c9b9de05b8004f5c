//! Load cases (issue #16): extra mass in the body, with its position, giving the car a
//! new sprung mass, centre of gravity and inertias.
//!
//! Convention: body axes at the base car's centre of gravity (CG), `x` forward (towards
//! the front axle), `y` lateral, `z` up, all in m. The car model is mirror-symmetric left
//! to right, so a load is placed symmetrically: half of `mass` at `(x, +y, z)` and half at
//! `(x, -y, z)` (`y = 0` puts all of it on the centre line). With base mass `M`, extra
//! mass `m` and `M' = M + m`:
//!
//! - sprung mass `M' = M + m`, kg;
//! - the CG moves forward by `dx = m x / M'` (and up by `m z / M'`), so
//!   `a' = a - dx`, `b' = b + dx` (the wheelbase is unchanged);
//! - pitch inertia about the new CG (parallel-axis theorem, the body's inertia moved by
//!   `(dx, dz)` and the load's by `(x - dx, z - dz)`):
//!   `Iyy' = Iyy + (M m / M') (x^2 + z^2)`, kg m^2;
//! - roll inertia `Ixx' = Ixx + (M m / M') z^2 + m y^2`, kg m^2 (the two halves at `±y`).
//!
//! A negative `mass` takes mass out (a lighter case than the car file's). The quarter car
//! follows from the loaded car as always: `ms = M' b' / (2 L)` and the front wheel's static
//! load `(ms + mu) g`.

use crate::car::Car;
use crate::error::{Result, RideError};
use serde::{Deserialize, Serialize};

/// Most load cases in a list.
pub const MAX_LOAD_CASES: usize = 16;
/// Longest case name, characters.
const MAX_NAME_CHARS: usize = 64;

/// One load case: extra mass in the body and where it sits (see the module docs for the
/// axes and the equations).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadCase {
    /// Name for reports ("driver only", "fully laden").
    pub name: String,
    /// Extra sprung mass, kg (negative takes mass out); 0 is the car as given.
    pub mass: f64,
    /// Position of the load ahead of the base CG, m (negative is behind it).
    #[serde(default)]
    pub x: f64,
    /// Lateral half-spacing of the load's two symmetric halves, m.
    #[serde(default)]
    pub y: f64,
    /// Height of the load above the base CG, m.
    #[serde(default)]
    pub z: f64,
    /// Weight of the case in a weighted mean (>= 0; default 1).
    #[serde(default = "one")]
    pub weight: f64,
}

fn one() -> f64 {
    1.0
}

impl LoadCase {
    /// The car as given: no extra mass.
    pub fn base() -> LoadCase {
        LoadCase {
            name: "as given".into(),
            mass: 0.0,
            x: 0.0,
            y: 0.0,
            z: 0.0,
            weight: 1.0,
        }
    }

    /// `car` with this load: new sprung mass, `a`, `b` and inertias (module docs). A zero
    /// mass returns `car` unchanged, bit for bit. Errors name `prefix.field`
    /// (`load_cases[1].mass`): a field not finite, a total mass not > 0, a CG outside the
    /// wheelbase (`x`), an inertia not > 0, a bad weight or name.
    pub fn apply(&self, car: &Car, prefix: &str) -> Result<Car> {
        let field = |f: &str| format!("{prefix}.{f}");
        use crate::domain::{CASE_WEIGHT, LOAD_MASS, LOAD_POSITION, LOAD_SPREAD};
        for (f, v, limit) in [
            ("mass", self.mass, &LOAD_MASS),
            ("x", self.x, &LOAD_POSITION),
            ("y", self.y.abs(), &LOAD_SPREAD),
            ("z", self.z, &LOAD_POSITION),
            ("weight", self.weight, &CASE_WEIGHT),
        ] {
            limit.check(&field(f), v)?;
        }
        if self.name.trim().is_empty() || self.name.chars().count() > MAX_NAME_CHARS {
            return Err(RideError::field(
                field("name"),
                format!("needs 1 to {MAX_NAME_CHARS} characters"),
            ));
        }
        if self.mass == 0.0 {
            return Ok(car.clone());
        }
        let (m, big_m) = (self.mass, car.sprung_mass);
        let total = big_m + m;
        if total <= 0.0 {
            return Err(RideError::field(
                field("mass"),
                format!(
                    "leaves a sprung mass of {total} kg (car {big_m} kg + {m} kg); it must stay > 0"
                ),
            ));
        }
        let dx = m * self.x / total;
        let (a, b) = (car.a - dx, car.b + dx);
        if !(a > 0.0 && b > 0.0) {
            return Err(RideError::field(
                field("x"),
                format!(
                    "moves the centre of gravity {dx:.3} m forward, outside the wheelbase (a = {a:.3} m, b = {b:.3} m; both must stay > 0)"
                ),
            ));
        }
        let reduced = big_m * m / total;
        let pitch = car.pitch_inertia + reduced * (self.x * self.x + self.z * self.z);
        let roll = car.roll_inertia + reduced * self.z * self.z + m * self.y * self.y;
        for (f, v) in [("pitch_inertia", pitch), ("roll_inertia", roll)] {
            if v <= 0.0 {
                return Err(RideError::field(
                    field("mass"),
                    format!("leaves a {f} of {v} kg m^2; it must stay > 0"),
                ));
            }
        }
        let loaded = Car {
            sprung_mass: total,
            a,
            b,
            pitch_inertia: pitch,
            roll_inertia: roll,
            ..car.clone()
        };
        loaded.validate().map_err(|e| match e {
            RideError::Field { field: f, reason } => {
                RideError::field(field("mass"), format!("{f}: {reason}"))
            }
            other => other,
        })?;
        Ok(loaded)
    }
}

/// Checks a list of load cases on `car` (each applies; 1 to [`MAX_LOAD_CASES`] of them,
/// names distinct); errors name `field[i].x` (`field` is `load_cases`).
pub(crate) fn check_load_cases(cases: &[LoadCase], car: &Car, field: &str) -> Result<Vec<Car>> {
    if cases.is_empty() {
        return Err(RideError::field(
            field,
            "is empty: list at least one case (leave the key out for the car as given)",
        ));
    }
    if cases.len() > MAX_LOAD_CASES {
        return Err(RideError::field(
            field,
            format!("at most {MAX_LOAD_CASES} cases, got {}", cases.len()),
        ));
    }
    let mut cars = Vec::with_capacity(cases.len());
    for (i, c) in cases.iter().enumerate() {
        if cases[..i].iter().any(|p| p.name == c.name) {
            return Err(RideError::field(
                format!("{field}[{i}].name"),
                format!("'{}' is used twice", c.name),
            ));
        }
        cars.push(c.apply(car, &format!("{field}[{i}]"))?);
    }
    Ok(cars)
}

/// A car file: the car ([`Car::from_json`]'s keys) and, optionally, its load cases
/// under the key `load_cases`.
#[derive(Debug, Clone, PartialEq)]
pub struct CarFile {
    /// The car as given.
    pub car: Car,
    /// Its load cases, empty when the file lists none.
    pub load_cases: Vec<LoadCase>,
}

impl CarFile {
    /// Parses a car file; the car is validated as [`Car::from_json`] does and the load
    /// cases by [`check_load_cases`] (errors name `load_cases[i].field`).
    pub fn from_json(text: &str) -> Result<CarFile> {
        // A file without load cases (or one that is not a JSON object) is read by
        // `Car::from_json` itself, so its result and messages are exactly that.
        let mut value = match serde_json::from_str::<serde_json::Value>(text) {
            Ok(v) if v.get("load_cases").is_some() => v,
            _ => {
                return Ok(CarFile {
                    car: Car::from_json(text)?,
                    load_cases: Vec::new(),
                })
            }
        };
        let cases = value
            .as_object_mut()
            .and_then(|o| o.remove("load_cases"))
            .unwrap_or_default();
        // serde_json's float_roundtrip feature writes every number back exactly.
        let car = Car::from_json(&value.to_string())?;
        let load_cases = parse_load_cases(cases, "load_cases")?;
        check_load_cases(&load_cases, &car, "load_cases")?;
        Ok(CarFile { car, load_cases })
    }
}

/// Deserialises a list of load cases from `value`; errors name `field[i].key`.
pub(crate) fn parse_load_cases(value: serde_json::Value, field: &str) -> Result<Vec<LoadCase>> {
    // Read from its text (compact, every number exact: serde_json's float_roundtrip), so
    // that an error has a position to find its field at (crate::json_path).
    let text = value.to_string();
    crate::json_path::from_str(&text).map_err(|(path, e)| {
        // The position is in that text, not the user's file: left out of the message.
        let message = e.to_string();
        let message = match message.rfind(" at line ") {
            Some(k) => message[..k].to_string(),
            None => message,
        };
        let path = if path.is_empty() {
            field.to_string()
        } else {
            format!(
                "{field}{}",
                if path.starts_with('[') {
                    path
                } else {
                    format!(".{path}")
                }
            )
        };
        RideError::field(path, message)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn case(mass: f64, x: f64, y: f64, z: f64) -> LoadCase {
        LoadCase {
            name: "test".into(),
            mass,
            x,
            y,
            z,
            weight: 1.0,
        }
    }

    /// Zero extra mass: the car as given, every field bit for bit.
    #[test]
    fn zero_mass_is_the_base_car() {
        let car = Car::datum();
        assert_eq!(case(0.0, 1.2, 0.4, 0.3).apply(&car, "c").unwrap(), car);
    }

    /// Mass at the CG: sprung mass M + m, CG and inertias unchanged to 1e-12 (relative).
    #[test]
    fn mass_at_the_cg_changes_the_mass_only() {
        let car = Car::datum();
        let l = case(350.0, 0.0, 0.0, 0.0).apply(&car, "c").unwrap();
        assert_eq!(l.sprung_mass, car.sprung_mass + 350.0);
        for (got, want) in [
            (l.a, car.a),
            (l.b, car.b),
            (l.pitch_inertia, car.pitch_inertia),
            (l.roll_inertia, car.roll_inertia),
        ] {
            assert!((got - want).abs() <= 1e-12 * want.abs(), "{got} {want}");
        }
        // The front corner's share follows: ms = (M + m) b / (2 L).
        let ms = (car.sprung_mass + 350.0) * car.b / (2.0 * car.wheelbase());
        assert!((l.quarter().ms - ms).abs() <= 1e-12 * ms);
    }

    /// A point mass ahead of the CG, checked against an independent sum over the two
    /// bodies (the base body as a point of mass M with its own inertia, the load as two
    /// halves): CG shift m d / (M + m), inertias by the parallel-axis theorem, 1e-12.
    #[test]
    fn mass_ahead_moves_the_cg_and_adds_parallel_axis_inertia() {
        let car = Car::datum();
        let (m, d, y, z) = (120.0, 0.8, 0.45, 0.2);
        let l = case(m, d, y, z).apply(&car, "c").unwrap();
        let big_m = car.sprung_mass;
        let total = big_m + m;
        // New CG from the first moments about the old CG.
        let xc = (big_m * 0.0 + m * d) / total;
        let zc = (big_m * 0.0 + m * z) / total;
        assert!((car.a - l.a - m * d / total).abs() < 1e-12);
        assert!((l.a - (car.a - xc)).abs() < 1e-12 && (l.b - (car.b + xc)).abs() < 1e-12);
        assert!((l.wheelbase() - car.wheelbase()).abs() < 1e-12);
        // Second moments about the new CG, body and each half of the load separately.
        let iyy = car.pitch_inertia
            + big_m * (xc * xc + zc * zc)
            + m * ((d - xc).powi(2) + (z - zc).powi(2));
        let ixx = car.roll_inertia
            + big_m * zc * zc
            + 0.5 * m * (y * y + (z - zc).powi(2))
            + 0.5 * m * (y * y + (z - zc).powi(2));
        assert!(
            (l.pitch_inertia / iyy - 1.0).abs() < 1e-12,
            "{} {iyy}",
            l.pitch_inertia
        );
        assert!(
            (l.roll_inertia / ixx - 1.0).abs() < 1e-12,
            "{} {ixx}",
            l.roll_inertia
        );
        assert_eq!(l.sprung_mass, total);
    }

    #[test]
    fn unphysical_cases_name_the_field() {
        let car = Car::datum();
        let e = |c: LoadCase| c.apply(&car, "load_cases[1]").unwrap_err().to_string();
        assert!(e(case(-1460.0, 0.0, 0.0, 0.0)).starts_with("load_cases[1].mass: "));
        // 1000 kg at 4 m ahead moves the CG 1.63 m forward, past the front axle (a = 1.011 m).
        assert!(e(case(1000.0, 4.0, 0.0, 0.0)).starts_with("load_cases[1].x: "));
        assert!(e(case(f64::NAN, 0.0, 0.0, 0.0)).starts_with("load_cases[1].mass: "));
        assert!(e(LoadCase {
            weight: -1.0,
            ..case(10.0, 0.0, 0.0, 0.0)
        })
        .starts_with("load_cases[1].weight: "));
        assert!(e(LoadCase {
            name: " ".into(),
            ..case(10.0, 0.0, 0.0, 0.0)
        })
        .starts_with("load_cases[1].name: "));
        // Taking out most of the mass far from the CG leaves a negative pitch inertia.
        assert!(e(case(-1400.0, 0.0, 0.0, 3.0)).starts_with("load_cases[1].mass: "));
        let many = vec![case(1.0, 0.0, 0.0, 0.0); MAX_LOAD_CASES + 1];
        let err = check_load_cases(&many, &car, "load_cases")
            .unwrap_err()
            .to_string();
        assert!(err.starts_with("load_cases: at most 16"), "{err}");
        let err = check_load_cases(&[], &car, "load_cases")
            .unwrap_err()
            .to_string();
        assert!(err.starts_with("load_cases: is empty"), "{err}");
        let twice = vec![case(1.0, 0.0, 0.0, 0.0); 2];
        let err = check_load_cases(&twice, &car, "load_cases")
            .unwrap_err()
            .to_string();
        assert!(err.starts_with("load_cases[1].name: "), "{err}");
    }

    #[test]
    fn car_file_with_and_without_load_cases() {
        let text = crate::car::PRESETS[0].1;
        let f = CarFile::from_json(text).unwrap();
        assert_eq!(f.car, Car::datum());
        assert!(f.load_cases.is_empty());
        let mut v: serde_json::Value = serde_json::from_str(text).unwrap();
        v["load_cases"] = serde_json::json!([
            {"name": "driver only", "mass": 0},
            {"name": "fully laden", "mass": 350, "x": -0.3}
        ]);
        let f = CarFile::from_json(&v.to_string()).unwrap();
        assert_eq!(f.load_cases.len(), 2);
        assert_eq!(f.load_cases[1].x, -0.3);
        assert_eq!(f.load_cases[1].weight, 1.0);
        v["load_cases"][1]["mass"] = serde_json::json!("heavy");
        let e = CarFile::from_json(&v.to_string()).unwrap_err().to_string();
        assert!(e.starts_with("load_cases[1].mass: "), "{e}");
        v["load_cases"][1]["mass"] = serde_json::json!(-2000);
        let e = CarFile::from_json(&v.to_string()).unwrap_err().to_string();
        assert!(e.starts_with("load_cases[1].mass: "), "{e}");
        v["load_cases"][1]["mas"] = serde_json::json!(1);
        let e = CarFile::from_json(&v.to_string()).unwrap_err().to_string();
        assert!(e.starts_with("load_cases[1]"), "{e}");
        v["load_cases"] = serde_json::json!([]);
        let e = CarFile::from_json(&v.to_string()).unwrap_err().to_string();
        assert!(e.starts_with("load_cases: "), "{e}");
    }
}
