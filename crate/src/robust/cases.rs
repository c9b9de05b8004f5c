//! The cases of a robust design (issue #16): every load case of the car at every
//! operating point (road class and speed), each with a weight, and how their criteria are
//! combined.
//!
//! The cases file (`ridelab map|optimize --cases FILE`):
//!
//! ```json
//! {
//!   "load_cases": [{"name": "driver only", "mass": 0},
//!                  {"name": "fully laden", "mass": 350, "x": -0.3}],
//!   "operating": [{"class": "B", "speed": 20, "weight": 2},
//!                 {"class": "C", "speed": 30}],
//!   "combine": "worst"
//! }
//! ```
//!
//! Every key is optional: `load_cases` defaults to the car file's (or the car as given),
//! `operating` to the command's `--class`/`--speed`, `combine` to `worst`. The cases are
//! the product load case x operating point, load-case-major (case `k = l * n_op + o`), each
//! with weight `w_load w_op`; at most [`MAX_CASES`] in all.

use super::load::{check_load_cases, parse_load_cases, LoadCase, MAX_LOAD_CASES};
use crate::car::Car;
use crate::error::{Result, RideError};
use crate::road::{Road, RoadClass};
use serde::{Deserialize, Serialize};

/// Most cases (load cases x operating points) of one robust design.
pub const MAX_CASES: usize = 16;

/// How the cases' criteria become the robust objective.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Combine {
    /// The worst case: the largest normalised value over the cases (weights unused).
    #[default]
    Worst,
    /// The weighted mean of the normalised values.
    Mean,
}

/// One operating point: road class, speed and weight (tracks are the command's).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Operating {
    /// ISO 8608 class.
    pub class: RoadClass,
    /// Speed, m/s.
    pub speed: f64,
    /// Weight in a weighted mean (>= 0; default 1).
    #[serde(default = "one")]
    pub weight: f64,
}

fn one() -> f64 {
    1.0
}

/// The cases file as written (every key optional).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CasesFile {
    /// Load cases (replacing the car file's).
    #[serde(default)]
    pub load_cases: Option<serde_json::Value>,
    /// Operating points.
    #[serde(default)]
    pub operating: Option<Vec<Operating>>,
    /// Worst case or weighted mean.
    #[serde(default)]
    pub combine: Combine,
}

/// One case: a loaded car on one road, with its (unnormalised) weight.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Case {
    /// `"<load case> / <class> at <speed> m/s"`.
    pub name: String,
    /// The loaded car.
    #[serde(skip)]
    pub car: Car,
    /// The road.
    pub road: Road,
    /// Weight `w_load w_op`.
    pub weight: f64,
    /// The load case.
    pub load: LoadCase,
}

/// The cases of a robust design and how they are combined.
#[derive(Debug, Clone, PartialEq)]
pub struct CaseSet {
    /// The cases, load-case-major.
    pub cases: Vec<Case>,
    /// Worst case or weighted mean.
    pub combine: Combine,
}

impl CaseSet {
    /// The cases of `load_cases` (empty: the car as given) at `operating` (empty: `road`)
    /// on `car`; `road.tracks` for all. Errors name the field (`load_cases[1].mass`,
    /// `operating[0].speed`, `operating`, `weight`).
    pub fn new(
        car: &Car,
        road: &Road,
        load_cases: &[LoadCase],
        operating: &[Operating],
        combine: Combine,
    ) -> Result<CaseSet> {
        let loads = if load_cases.is_empty() {
            vec![LoadCase::base()]
        } else {
            load_cases.to_vec()
        };
        let cars = check_load_cases(&loads, car, "load_cases")?;
        let ops = if operating.is_empty() {
            vec![Operating {
                class: road.class,
                speed: road.speed,
                weight: 1.0,
            }]
        } else {
            check_operating(operating)?;
            operating.to_vec()
        };
        if loads.len() * ops.len() > MAX_CASES {
            return Err(RideError::field(
                "operating",
                format!(
                    "{} load cases x {} operating points = {} cases; at most {MAX_CASES}",
                    loads.len(),
                    ops.len(),
                    loads.len() * ops.len()
                ),
            ));
        }
        let mut cases = Vec::with_capacity(loads.len() * ops.len());
        for (load, car) in loads.iter().zip(cars) {
            for op in &ops {
                let r = Road {
                    class: op.class,
                    speed: op.speed,
                    tracks: road.tracks,
                };
                cases.push(Case {
                    name: format!("{} / {:?} at {} m/s", load.name, op.class, op.speed),
                    car: car.clone(),
                    road: r,
                    weight: load.weight * op.weight,
                    load: load.clone(),
                });
            }
        }
        let total: f64 = cases.iter().map(|c| c.weight).sum();
        if !(total.is_finite() && total > 0.0) {
            return Err(RideError::field(
                "weight",
                format!("the case weights (load case weight x operating weight) sum to {total}; they must sum to a number > 0"),
            ));
        }
        Ok(CaseSet { cases, combine })
    }

    /// The cases of a cases file's text over `car` (whose own load cases are
    /// `car_load_cases`) on `road`.
    pub fn from_json(
        text: &str,
        car: &Car,
        car_load_cases: &[LoadCase],
        road: &Road,
    ) -> Result<CaseSet> {
        crate::car::check_object("cases", "a cases file", text)?;
        let file: CasesFile = crate::json_path::from_str(text).map_err(|(path, inner)| {
            if path.is_empty() {
                RideError::Json(inner.to_string())
            } else {
                RideError::field(path, inner.to_string())
            }
        })?;
        let loads = match file.load_cases {
            Some(v) => {
                let l = parse_load_cases(v, "load_cases")?;
                if l.is_empty() {
                    return Err(RideError::field(
                        "load_cases",
                        "is empty: list at least one case (leave the key out for the car's)",
                    ));
                }
                l
            }
            None => car_load_cases.to_vec(),
        };
        let ops = match file.operating {
            Some(o) if o.is_empty() => {
                return Err(RideError::field(
                    "operating",
                    "is empty: list at least one {\"class\", \"speed\"} (leave the key out for --class and --speed)",
                ))
            }
            Some(o) => o,
            None => Vec::new(),
        };
        CaseSet::new(car, road, &loads, &ops, file.combine)
    }

    /// The runs of consecutive cases on one loaded car (equal [`Case::car`]), in case
    /// order: one run per load case of a load-case-major set (two load cases that load
    /// the car alike make one run).
    pub(crate) fn car_runs(&self) -> Vec<std::ops::Range<usize>> {
        let mut runs: Vec<std::ops::Range<usize>> = Vec::new();
        for (k, c) in self.cases.iter().enumerate() {
            match runs.last_mut() {
                Some(run) if self.cases[run.start].car == c.car => run.end = k + 1,
                _ => runs.push(k..k + 1),
            }
        }
        runs
    }

    /// Weights normalised to sum to 1, `p_k = w_k / sum w` (one case: exactly 1).
    pub(crate) fn probabilities(&self) -> Vec<f64> {
        let total: f64 = self.cases.iter().map(|c| c.weight).sum();
        self.cases.iter().map(|c| c.weight / total).collect()
    }
}

/// Checks operating points: 1 to [`MAX_LOAD_CASES`], speeds as [`Road::validate`],
/// weights finite and >= 0; errors name `operating[i].field`.
fn check_operating(ops: &[Operating]) -> Result<()> {
    if ops.len() > MAX_LOAD_CASES {
        return Err(RideError::field(
            "operating",
            format!(
                "at most {MAX_LOAD_CASES} operating points, got {}",
                ops.len()
            ),
        ));
    }
    for (i, o) in ops.iter().enumerate() {
        let road = Road {
            class: o.class,
            speed: o.speed,
            ..Road::default()
        };
        road.validate().map_err(|e| match e {
            RideError::Field { reason, .. } => {
                RideError::field(format!("operating[{i}].speed"), reason)
            }
            other => other,
        })?;
        crate::domain::CASE_WEIGHT.check(&format!("operating[{i}].weight"), o.weight)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn set(text: &str) -> Result<CaseSet> {
        CaseSet::from_json(text, &Car::datum(), &[], &Road::default())
    }

    #[test]
    fn product_of_load_cases_and_operating_points() {
        let s = set(r#"{"load_cases": [{"name": "a", "mass": 0, "weight": 2}, {"name": "b", "mass": 100}],
                        "operating": [{"class": "B", "speed": 10}, {"class": "C", "speed": 30, "weight": 3}],
                        "combine": "mean"}"#)
        .unwrap();
        assert_eq!(s.cases.len(), 4);
        assert_eq!(s.combine, Combine::Mean);
        let w: Vec<f64> = s.cases.iter().map(|c| c.weight).collect();
        assert_eq!(w, vec![2.0, 6.0, 1.0, 3.0]);
        assert_eq!(s.cases[1].road.class, RoadClass::C);
        assert_eq!(s.cases[1].name, "a / C at 30 m/s");
        assert_eq!(s.cases[2].car.sprung_mass, 1560.0);
        let p = s.probabilities();
        assert!((p.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        let one = set("{}").unwrap();
        assert_eq!(one.cases.len(), 1);
        assert_eq!(one.probabilities(), vec![1.0]);
        assert_eq!(one.cases[0].car, Car::datum());
        assert_eq!(one.cases[0].road, Road::default());
    }

    #[test]
    fn bad_cases_name_the_field() {
        let e = |t: &str| set(t).unwrap_err().to_string();
        assert!(e(r#"{"load_cases": []}"#).starts_with("load_cases: is empty"));
        assert!(e(r#"{"operating": []}"#).starts_with("operating: is empty"));
        assert!(e(r#"{"operating": [{"class": "B", "speed": -3}]}"#)
            .starts_with("operating[0].speed: "));
        assert!(
            e(r#"{"operating": [{"class": "Q", "speed": 3}]}"#).starts_with("operating[0].class")
        );
        assert!(
            e(r#"{"operating": [{"class": "B", "speed": 3, "weight": -1}]}"#)
                .starts_with("operating[0].weight: ")
        );
        assert!(
            e(r#"{"operating": [{"class": "B", "speed": 3, "weight": 0}]}"#)
                .starts_with("weight: ")
        );
        assert!(
            e(r#"{"load_cases": [{"name": "x", "mass": 10}, {"name": "y", "mass": -5000}]}"#)
                .starts_with("load_cases[1].mass: ")
        );
        assert!(e(r#"{"combine": "median"}"#).starts_with("combine: "));
        assert!(e(r#"{"combin": "mean"}"#).contains("combin"));
        let ops: Vec<String> = (0..5)
            .map(|i| format!(r#"{{"class": "B", "speed": {}}}"#, 10 + i))
            .collect();
        let loads: Vec<String> = (0..4)
            .map(|i| format!(r#"{{"name": "l{i}", "mass": {i}}}"#))
            .collect();
        let t = format!(
            r#"{{"load_cases": [{}], "operating": [{}]}}"#,
            loads.join(","),
            ops.join(",")
        );
        assert!(e(&t)
            .starts_with("operating: 4 load cases x 5 operating points = 20 cases; at most 16"));
    }
}
