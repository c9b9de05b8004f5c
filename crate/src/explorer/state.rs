//! The explorer's state (what the page sends, field names camelCase), and its conversion
//! into core types.
//!
//! Units follow the core (SI): `ks` N/m, `cs` N s/m, `speed` m/s, `swsLimit` m,
//! `bounceBand` Hz. The UI converts to kN/m, kNs/m and mm for display only.

use super::road_source::RoadSource;
use crate::analysis::ModelKind;
use crate::car::Car;
use crate::comfort::Comfort;
use crate::design::DesignBox;
use crate::dos::DesignObjectives;
use crate::error::{Result, RideError};
use crate::evaluate::Evaluator;
use crate::optimize::PickRule;
use crate::road::{Road, RoadClass, Tracks};
use crate::robust::{CarFile, CaseSet};
use crate::study::{StudyRoad, StudySpec};
use crate::surrogate::{PlanSpec, SurrogateSpec};
use crate::LoFi;
use serde::{Deserialize, Serialize};
use std::rc::Rc;
use std::sync::Arc;

/// The state fields a surrogate's fit and every map's values depend on (those of
/// [`super::FitKey`]; the objectives only judge a map; the comfort measure fills the
/// LoFi and HiFi maps' BAcc plane): two states equal in these fields have the same fit
/// and maps (tested). The page keys its fits and maps by them.
pub const FIT_FIELDS: [&str; 14] = [
    "car",
    "carJson",
    "class",
    "roadProfile",
    "speed",
    "tracks",
    "ksMin",
    "ksMax",
    "csMin",
    "csMax",
    "surrogate",
    "plan",
    "comfort",
    "cases",
];

/// The state fields a design's LoFi and HiFi reports depend on: the car, the design and
/// the road. The page keys its HiFi readout by them.
pub const REPORT_FIELDS: [&str; 8] = [
    "car",
    "carJson",
    "ks",
    "cs",
    "class",
    "roadProfile",
    "speed",
    "tracks",
];

/// The JS names of the [`State`] fields.
pub const STATE_FIELDS: [&str; 24] = [
    "car",
    "carJson",
    "ks",
    "cs",
    "class",
    "roadProfile",
    "speed",
    "tracks",
    "ksMin",
    "ksMax",
    "csMin",
    "csMax",
    "swsLimit",
    "bounceBand",
    "dampingBand",
    "noWorse",
    "dtlMargin",
    "travel",
    "surrogate",
    "plan",
    "comfort",
    "pick",
    "cases",
    "case",
];

/// The explorer's surrogate unless the state names one: the best of the fidelity study
/// at 10 samples (max RTE under 0.7 % on the datum car).
const DEFAULT_SURROGATE: &str = "rba-mul-rbf-mq";
/// The explorer's sampling plan unless the state names one.
const DEFAULT_PLAN: &str = "ae:10";
/// Most HiFi samples a plan may ask for in the explorer (a fit stays a few ms).
pub const MAX_PLAN_POINTS: usize = 100;
/// Longest cases text (`cases`), characters: 16 load cases and 16 operating points with
/// long names fit in a few kB.
const MAX_CASES_CHARS: usize = 16_384;

/// Everything the page needs to define one view: car, design point, road, design box
/// and the SWS objective. Field names are camelCase on the JS side.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
pub struct State {
    /// A preset name ("sedan", "compact", "suv") or "custom" (then `car_json` is the car file).
    pub car: String,
    /// The car file when `car` is "custom".
    #[serde(default)]
    pub car_json: Option<String>,
    /// Front spring rate, N/m.
    pub ks: f64,
    /// Front damper rate, N s/m.
    pub cs: f64,
    /// ISO 8608 class "A".."H".
    pub class: String,
    /// A measured road in place of the class (#31): the key under which the caller
    /// registered the profile (the page's `useRoad`), which the session's
    /// [`RoadResolver`] shapes at the state's speed with its tracks. Absent: the class
    /// (and left out of the state the core hands back).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub road_profile: Option<String>,
    /// Vehicle speed, m/s.
    pub speed: f64,
    /// "correlated" or "independent".
    pub tracks: String,
    /// Design box: lowest Ks, N/m (default [`DesignBox::default`]).
    #[serde(default)]
    pub ks_min: Option<f64>,
    /// Design box: highest Ks, N/m.
    #[serde(default)]
    pub ks_max: Option<f64>,
    /// Design box: lowest Cs, N s/m.
    #[serde(default)]
    pub cs_min: Option<f64>,
    /// Design box: highest Cs, N s/m.
    #[serde(default)]
    pub cs_max: Option<f64>,
    /// RMS SWS limit, m (default 0.007).
    #[serde(default)]
    pub sws_limit: Option<f64>,
    /// Allowed body-bounce frequency band `[lo, hi]`, Hz (off when absent).
    #[serde(default)]
    pub bounce_band: Option<[f64; 2]>,
    /// Allowed body damping-ratio band `[lo, hi]`, - (off when absent).
    #[serde(default)]
    pub damping_band: Option<[f64; 2]>,
    /// "No worse than the datum car" for `[BAcc, DTL, SWS]` (all off when absent).
    #[serde(default)]
    pub no_worse: Option<[bool; 3]>,
    /// Tyre-load margin `k`: RMS DTL at most the static wheel load / k (off when absent).
    #[serde(default)]
    pub dtl_margin: Option<f64>,
    /// Travel budget `[available bump travel m, sigma factor]` (off when absent).
    #[serde(default)]
    pub travel: Option<[f64; 2]>,
    /// The surrogate, a `ridelab surrogate` name (default [`DEFAULT_SURROGATE`]).
    #[serde(default)]
    pub surrogate: Option<String>,
    /// Its sampling plan, `ae:N` or `grid:n` (default [`DEFAULT_PLAN`]).
    #[serde(default)]
    pub plan: Option<String>,
    /// The comfort objective of the LoFi and HiFi maps, the design objectives, the front
    /// and the pick: "bacc" (unweighted RMS body acceleration, the default) or "wk"
    /// (ISO 2631-1 Wk-weighted RMS body acceleration), m/s^2 ([`Comfort`]). The
    /// surrogates are fitted to the unweighted BAcc: their maps stay BAcc.
    #[serde(default)]
    pub comfort: Option<String>,
    /// The pick on the front: "minmax" (the thesis's, the default), "knee" or "asf:W"
    /// with comfort weight `0 <= W <= 1` ([`PickRule`]).
    #[serde(default)]
    pub pick: Option<String>,
    /// The robust design's cases (issue #16): the text of a cases file as `ridelab map
    /// --cases FILE` reads it (`{"load_cases": [{name, mass kg, x, y, z m, weight}],
    /// "operating": [{class, speed m/s, weight}], "combine": "worst" | "mean"}`, every
    /// key optional, at most [`crate::robust::MAX_CASES`] cases, at most
    /// [`MAX_CASES_CHARS`] characters) over the datum car on the state's road. Absent: one
    /// case, the car as given.
    #[serde(default)]
    pub cases: Option<String>,
    /// What the LoFi and HiFi maps show with cases: "robust" (the default) or a case
    /// index "0".."15" (load-case-major, as `ridelab map --case K`).
    #[serde(default)]
    pub case: Option<String>,
}

impl Default for State {
    /// The datum car at its own front spring and damper, class B at 20 m/s, correlated.
    fn default() -> Self {
        let car = Car::datum();
        let road = Road::default();
        let b = DesignBox::default();
        State {
            car: crate::car::PRESETS[0].0.to_string(),
            car_json: None,
            ks: car.front.spring,
            cs: car.front.damper,
            class: format!("{:?}", road.class),
            road_profile: None,
            speed: road.speed,
            tracks: "correlated".into(),
            ks_min: Some(b.ks_min),
            ks_max: Some(b.ks_max),
            cs_min: Some(b.cs_min),
            cs_max: Some(b.cs_max),
            sws_limit: DesignObjectives::default().sws_limit,
            bounce_band: None,
            damping_band: None,
            no_worse: None,
            dtl_margin: None,
            travel: None,
            surrogate: Some(DEFAULT_SURROGATE.into()),
            plan: Some(DEFAULT_PLAN.into()),
            comfort: Some("bacc".into()),
            pick: Some("minmax".into()),
            cases: None,
            case: None,
        }
    }
}

/// The core objects behind a [`State`].
#[derive(Debug, Clone, PartialEq)]
pub struct Scenario {
    /// The datum car: the chosen car with its own front spring and damper.
    pub datum: Car,
    /// The datum car with the front set to the state's design.
    pub design: Car,
    /// The road: the ISO class, or with [`Scenario::measured`] its speed and tracks only.
    pub road: Road,
    /// The measured road in place of the class (`None`: the class).
    pub measured: Option<Measured>,
    /// The design box.
    pub dbox: DesignBox,
    /// The design objectives.
    pub objectives: DesignObjectives,
    /// The surrogate to fit.
    pub surrogate: SurrogateSpec,
    /// Its sampling plan.
    pub plan: PlanSpec,
    /// The comfort measure in the LoFi's and HiFi's BAcc slot.
    pub comfort: Comfort,
    /// The pick rule on the front.
    pub pick: PickRule,
    /// The robust design's cases over the datum car (`None`: the car as given, one case).
    pub cases: Option<CaseSet>,
    /// The case the LoFi and HiFi maps show (`None`: the robust maps).
    pub case: Option<usize>,
}

/// Turns a state's `roadProfile` key into the road at a speed (m/s) with the state's
/// tracks, or an error naming `road` (the page's: the profiles `useRoad` registered).
pub type RoadResolver = Rc<dyn Fn(&str, f64, Tracks) -> Result<Arc<dyn RoadSource>>>;

/// A scenario's measured road; two are equal when their keys are (the same profile at
/// the same speed with the same tracks).
#[derive(Debug, Clone)]
pub struct Measured(pub Arc<dyn RoadSource>);

impl PartialEq for Measured {
    fn eq(&self, other: &Measured) -> bool {
        self.0.key() == other.0.key()
    }
}

impl State {
    /// The datum car (a preset or the custom car file), validated.
    fn datum_car(&self) -> Result<Car> {
        self.datum_car_file().map(|f| f.car)
    }

    /// The datum car and the load cases its file lists (none for a preset), as
    /// `ridelab --car FILE` reads a car file; validated (load case errors name
    /// `load_cases[i].field`).
    fn datum_car_file(&self) -> Result<CarFile> {
        if self.car == "custom" {
            let text = self
                .car_json
                .as_deref()
                .ok_or_else(|| RideError::field("car", "'custom' needs a car file (carJson)"))?;
            CarFile::from_json(text)
        } else {
            Ok(CarFile {
                car: Car::preset(&self.car)?,
                load_cases: Vec::new(),
            })
        }
    }

    /// The road, validated.
    pub fn road(&self) -> Result<Road> {
        let road = Road {
            class: RoadClass::parse(&self.class)?,
            speed: self.speed,
            tracks: Tracks::parse(&self.tracks)?,
        };
        road.validate()?;
        Ok(road)
    }

    /// The design box, validated.
    pub fn design_box(&self) -> Result<DesignBox> {
        let d = DesignBox::default();
        let b = DesignBox {
            ks_min: self.ks_min.unwrap_or(d.ks_min),
            ks_max: self.ks_max.unwrap_or(d.ks_max),
            cs_min: self.cs_min.unwrap_or(d.cs_min),
            cs_max: self.cs_max.unwrap_or(d.cs_max),
        };
        b.validate()?;
        Ok(b)
    }

    /// The design objectives, validated.
    pub fn objectives(&self) -> Result<DesignObjectives> {
        let o = DesignObjectives {
            sws_limit: self.sws_limit,
            bounce_band: self.bounce_band.map(|[lo, hi]| (lo, hi)),
            damping_band: self.damping_band.map(|[lo, hi]| (lo, hi)),
            no_worse_than_datum: self.no_worse.unwrap_or_default(),
            dtl_margin: self.dtl_margin,
            travel: self.travel.map(|[m, n]| (m, n)),
        };
        o.validate()?;
        Ok(o)
    }

    /// The surrogate and its plan, validated (errors name `approach` or `plan`).
    pub fn surrogate(&self) -> Result<(SurrogateSpec, PlanSpec)> {
        let spec = SurrogateSpec::parse(self.surrogate.as_deref().unwrap_or(DEFAULT_SURROGATE))?;
        let plan = PlanSpec::parse(self.plan.as_deref().unwrap_or(DEFAULT_PLAN))?;
        let points = match plan {
            PlanSpec::AudzeEglais(n) => n,
            PlanSpec::Grid(n) => n.saturating_mul(n),
        };
        if points < 2 {
            return Err(RideError::field(
                "plan",
                format!("{} has fewer than 2 points", plan.name()),
            ));
        }
        if points > MAX_PLAN_POINTS {
            return Err(RideError::field(
                "plan",
                format!(
                    "{} asks for {points} HiFi samples; the explorer takes at most {MAX_PLAN_POINTS}",
                    plan.name()
                ),
            ));
        }
        Ok((spec, plan))
    }

    /// The comfort measure and the pick rule, validated (errors name `comfort` or `pick`).
    fn criteria_choice(&self) -> Result<(Comfort, PickRule)> {
        let comfort = Comfort::parse(self.comfort.as_deref().unwrap_or("bacc"))?;
        let pick = self
            .pick
            .as_deref()
            .unwrap_or("minmax")
            .parse::<PickRule>()?;
        Ok((comfort, pick))
    }

    /// The cases over `datum` on `road` (`None` without `cases`), validated: errors name
    /// the field under `cases` (`cases.load_cases[1].mass`, `cases.operating[0].speed`,
    /// `cases` for text that is not JSON or too long), as `ridelab map --cases` does
    /// without the prefix.
    fn case_set(&self, datum: &Car, road: &Road) -> Result<Option<CaseSet>> {
        let Some(text) = self.cases.as_deref() else {
            return Ok(None);
        };
        let chars = text.chars().count();
        if chars > MAX_CASES_CHARS {
            return Err(RideError::field(
                "cases",
                format!("is {chars} characters long; at most {MAX_CASES_CHARS}"),
            ));
        }
        // `load_cases` defaults to the car file's, as `ridelab map --cases` reads it.
        let loads = self.datum_car_file()?.load_cases;
        CaseSet::from_json(text, datum, &loads, road)
            .map(Some)
            .map_err(|e| match e {
                RideError::Field { field, reason } if field == "cases" => {
                    RideError::field(field, reason)
                }
                RideError::Field { field, reason } => {
                    RideError::field(format!("cases.{field}"), reason)
                }
                RideError::Json(msg) => RideError::field("cases", msg),
                other => other,
            })
    }

    /// The case the maps show among `n` cases (`None`: robust); errors name `case`.
    fn case_index(&self, n: Option<usize>) -> Result<Option<usize>> {
        let choice = self.case.as_deref().unwrap_or("robust");
        if choice == "robust" {
            return Ok(None);
        }
        let Some(n) = n else {
            return Err(RideError::field(
                "case",
                format!("'{choice}' needs cases: without them the maps show the car as given"),
            ));
        };
        match choice.parse::<usize>() {
            Ok(k) if k < n => Ok(Some(k)),
            _ => Err(RideError::field(
                "case",
                format!("'{choice}' is not 'robust' or a case index 0..{}", n - 1),
            )),
        }
    }

    /// Everything at once; the first error names its field. A state with `roadProfile`
    /// needs a resolver ([`State::scenario_on`]).
    pub fn scenario(&self) -> Result<Scenario> {
        self.scenario_after(None, None)
    }

    /// [`State::scenario`] with `roads` to resolve a `roadProfile`.
    pub fn scenario_on(&self, roads: &RoadResolver) -> Result<Scenario> {
        self.scenario_after(None, Some(roads))
    }

    /// The measured road of `roadProfile` at the road's speed and tracks (`None` without
    /// one), re-using `previous`'s when those did not change; errors name `road` or
    /// `cases` (a measured road is one scenario: the robust cases take ISO classes).
    fn measured(
        &self,
        road: &Road,
        previous: Option<(&State, &Scenario)>,
        roads: Option<&RoadResolver>,
    ) -> Result<Option<Measured>> {
        let Some(key) = self.road_profile.as_deref() else {
            return Ok(None);
        };
        if self.cases.is_some() {
            return Err(RideError::field(
                "cases",
                "a measured road is one scenario: the robust cases take ISO classes (choose a class in the road menu)",
            ));
        }
        if let Some((p, s)) = previous {
            if p.road_profile == self.road_profile && s.road == *road && s.measured.is_some() {
                return Ok(s.measured.clone());
            }
        }
        let roads = roads.ok_or_else(|| {
            RideError::field(
                "road",
                format!("the measured road '{key}' is not loaded here"),
            )
        })?;
        Ok(Some(Measured(roads(key, road.speed, road.tracks)?)))
    }

    /// The scenario of this state, re-using the parts of `previous` (a state and its
    /// scenario) whose fields did not change: a slider move re-parses neither a custom
    /// car's file nor the surrogate's name. The first error names its field.
    pub(crate) fn scenario_after(
        &self,
        previous: Option<(&State, &Scenario)>,
        roads: Option<&RoadResolver>,
    ) -> Result<Scenario> {
        let datum = match previous {
            Some((p, s)) if p.car == self.car && p.car_json == self.car_json => s.datum.clone(),
            _ => self.datum_car()?,
        };
        let road = match previous {
            Some((p, s))
                if p.class == self.class && p.speed == self.speed && p.tracks == self.tracks =>
            {
                s.road
            }
            _ => self.road()?,
        };
        let measured = self.measured(&road, previous, roads)?;
        let design = datum.with_front(self.ks, self.cs)?;
        let (surrogate, plan) = match previous {
            Some((p, s)) if p.surrogate == self.surrogate && p.plan == self.plan => {
                (s.surrogate, s.plan)
            }
            _ => self.surrogate()?,
        };
        let (comfort, pick) = self.criteria_choice()?;
        let cases = match previous {
            Some((p, s))
                if p.cases == self.cases
                    && p.car_json == self.car_json
                    && s.datum == datum
                    && s.road == road =>
            {
                s.cases.clone()
            }
            _ => self.case_set(&datum, &road)?,
        };
        let case = self.case_index(cases.as_ref().map(|c| c.cases.len()))?;
        let dbox = self.design_box()?;
        dbox.check_on(&datum.design_domain())?;
        Ok(Scenario {
            datum,
            design,
            road,
            measured,
            dbox,
            objectives: self.objectives()?,
            surrogate,
            plan,
            comfort,
            pick,
            cases,
            case,
        })
    }
}

impl Scenario {
    /// The study this scenario is (issue #28): its car, road (the ISO class, or the
    /// measured road's source), design box, objectives, comfort measure and cases, on the
    /// CPU. What a study's methods compute from it is what the CLI computes from the same
    /// inputs ([`StudySpec`]'s methods are the CLI's).
    pub fn study(&self) -> StudySpec {
        StudySpec {
            car: self.datum.clone(),
            road: match &self.measured {
                Some(m) => StudyRoad::Measured(m.0.source().clone()),
                None => StudyRoad::Iso(self.road),
            },
            design_box: self.dbox,
            objectives: self.objectives.clone(),
            comfort: self.comfort,
            cases: self.cases.clone(),
            compute: None,
        }
    }

    /// The LoFi evaluator of the datum car on the road.
    pub fn lofi(&self) -> LoFi {
        LoFi::new(&self.datum, &self.road)
    }

    /// The HiFi evaluator of the datum car on the road.
    pub fn hifi(&self) -> Result<crate::HiFi> {
        crate::HiFi::new(&self.datum, &self.road)
    }

    /// The LoFi (`quarter`) or HiFi (`full`) evaluator of the datum car on the road with
    /// the scenario's comfort measure in the BAcc slot ([`Comfort::evaluator`]: with Wk,
    /// the exact Wk-weighted RMS body acceleration, m/s^2, as `ridelab map --comfort wk`).
    /// On a measured road, that model there.
    pub fn evaluator(&self, model: ModelKind) -> Result<Box<dyn Evaluator + Sync>> {
        self.evaluator_with(model, self.comfort)
    }

    /// [`Scenario::evaluator`] with `comfort` in the BAcc slot.
    pub fn evaluator_with(
        &self,
        model: ModelKind,
        comfort: Comfort,
    ) -> Result<Box<dyn Evaluator + Sync>> {
        match &self.measured {
            Some(m) => Ok(m.0.evaluator(model, &self.datum, comfort)),
            None => comfort.evaluator(model, &self.datum, &self.road),
        }
    }

    /// An error naming `road` when the scenario is on a measured road: the GPU path's
    /// values (its kernel is the ISO road's) are refused there; the CPU computes them.
    pub fn gpu_on_iso(&self) -> Result<()> {
        match &self.measured {
            Some(m) => Err(RideError::field(
                "road",
                format!(
                    "the GPU path computes an ISO 8608 class; the measured road {} runs on the CPU",
                    m.0.summary().file
                ),
            )),
            None => Ok(()),
        }
    }
}
