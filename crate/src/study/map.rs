//! The map report behind `ridelab map`: criteria fields, datum point, feasibility mask
//! and contour lines at automatic levels, as JSON (serde) or CSV.

use super::model::EvaluatorSpec;
use crate::analysis::{HiFi, LoFi, ModelKind};
use crate::car::Car;
use crate::comfort::Comfort;
use crate::design::DesignBox;
use crate::dos::{DesignObjectives, DosContext, Objective};
use crate::error::{Result, RideError};
use crate::evaluate::Evaluator;
use crate::gpu::{Compute, ComputePath, HiFiGrid};
use crate::maps::contour::{auto_levels, contour, contours, Contour};
use crate::maps::dcs::default_threads;
use crate::maps::dcs::{DatumPoint, Dcs, Scale};
use crate::maps::dos_mask::{
    objective_bit, objective_name, objectives_in, DosMap, DosSummary, FeasiblePoint,
};
use crate::maps::grid::Grid;
use crate::road::Road;
use crate::road_profile::RoadScenario;
use crate::surrogate::PlanSpec;
use serde::{Deserialize, Serialize};

/// The layout sentence every report carries.
pub const LAYOUT: &str =
    "row-major: Cs rows, Ks columns; the value at Ks index i, Cs index j is at j * ks.n + i";

/// Why a surrogate's map has no Wk-weighted comfort (the error names `comfort`).
pub(crate) const WK_SURROGATE_MAP: &str =
    "wk needs --model quarter or full: the surrogates are fitted to the unweighted BAcc";

/// Most automatic contour levels per criterion.
const MAX_CONTOUR_LEVELS: usize = 50;

/// What to map besides the model, car and road.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MapSettings {
    /// The Ks x Cs grid (default 41 x 41 over the default design box).
    pub grid: Grid,
    /// Absolute values or ratios to the datum car (default absolute).
    pub scale: Scale,
    /// Design objectives of the feasibility mask (default: SWS <= 7 mm).
    pub objectives: DesignObjectives,
    /// Automatic contour levels per criterion, at most (default 10, 0 for none).
    pub contour_levels: usize,
    /// The comfort measure in the BAcc field (default the unweighted BAcc; left out of
    /// the JSON then).
    #[serde(skip_serializing_if = "Comfort::is_bacc")]
    pub comfort: Comfort,
}

impl Default for MapSettings {
    fn default() -> Self {
        MapSettings {
            grid: Grid::default(),
            scale: Scale::Absolute,
            objectives: DesignObjectives::default(),
            contour_levels: 10,
            comfort: Comfort::Bacc,
        }
    }
}

impl MapSettings {
    /// Checks the grid (its axes inside the design domain, [`crate::domain`]), the
    /// objectives and the level count.
    pub fn validate(&self) -> Result<()> {
        self.grid.validate()?;
        self.grid.design_box().validate()?;
        self.objectives.validate()?;
        if self.contour_levels > MAX_CONTOUR_LEVELS {
            return Err(RideError::field(
                "contour_levels",
                format!("at most {MAX_CONTOUR_LEVELS}, got {}", self.contour_levels),
            ));
        }
        Ok(())
    }
}

/// Units of the report's quantities.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Units {
    /// Front spring rate.
    pub ks: &'static str,
    /// Front damper rate.
    pub cs: &'static str,
    /// BAcc field.
    pub bacc: &'static str,
    /// DTL field.
    pub dtl: &'static str,
    /// SWS field.
    pub sws: &'static str,
}

/// One bit of the feasibility mask.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct MaskBit {
    /// The objective (serialised as its name, e.g. `sws_limit`).
    pub objective: Objective,
    /// Its bit in `mask`.
    pub bit: u8,
    /// Human-readable label.
    pub label: &'static str,
}

/// The feasibility part of a map report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Feasibility {
    /// The objectives as given.
    pub objectives: DesignObjectives,
    /// The bits of the active objectives.
    pub legend: Vec<MaskBit>,
    /// Per point, the OR of the bits of the objectives it breaks (0 = feasible); map layout.
    pub mask: Vec<u8>,
    /// Counts per objective, and why nothing is feasible when that is so.
    pub summary: DosSummary,
    /// The feasible points in the BAcc-DTL plane, absolute criteria.
    pub feasible_set: Vec<FeasiblePoint>,
    /// Outline of the feasible region: the 0.5 contour of the 1/0 feasibility field.
    pub outline: Contour,
}

/// Contour lines per criterion, at automatic levels in the map's scale.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CriteriaContours {
    /// BAcc contours.
    pub bacc: Vec<Contour>,
    /// DTL contours.
    pub dtl: Vec<Contour>,
    /// SWS contours.
    pub sws: Vec<Contour>,
}

/// Everything `ridelab map` prints.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MapReport {
    /// Evaluator name ("quarter", "full", ...).
    pub evaluator: String,
    /// Car name.
    pub car: String,
    /// Road scenario: an ISO class (the fields of [`Road`]) or a measured profile.
    pub road: RoadScenario,
    /// Absolute or relative to the datum.
    pub scale: Scale,
    /// The grid.
    pub grid: Grid,
    /// Ks values of the columns, N/m.
    pub ks_values: Vec<f64>,
    /// Cs values of the rows, N s/m.
    pub cs_values: Vec<f64>,
    /// How the fields are laid out ([`LAYOUT`]).
    pub layout: &'static str,
    /// Units.
    pub units: Units,
    /// The comfort measure in `bacc` (and the datum's): `"wk"` for the ISO 2631-1
    /// Wk-weighted RMS body acceleration, m/s^2; left out for the unweighted BAcc.
    #[serde(skip_serializing_if = "Comfort::is_bacc")]
    pub comfort: Comfort,
    /// The datum design and its absolute criteria.
    pub datum: DatumPoint,
    /// BAcc field.
    pub bacc: Vec<f64>,
    /// DTL field.
    pub dtl: Vec<f64>,
    /// SWS field.
    pub sws: Vec<f64>,
    /// Feasibility mask and feasible set.
    pub feasibility: Feasibility,
    /// Contour lines.
    pub contours: CriteriaContours,
    /// The path that computed the fields: `"gpu"` or `"cpu"`.
    pub compute: ComputePath,
    /// The GPU adapter's name when the GPU computed the fields.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub adapter: Option<String>,
}

/// One map as `ridelab map` asks for it: the criteria of `car`'s front spring and damper
/// over `settings.grid` on `road` by `model`, the datum design the car's own front spring
/// and damper, with the feasibility mask of `settings.objectives` against the datum and
/// contour lines, in `settings.scale`. [`Self::run`] maps it on the model itself,
/// [`Self::run_on`] on an evaluator built already; [`Self::run_case`] and
/// [`Self::run_robust`] map it over load cases. The datum's criteria are the model's own
/// (a surrogate's map judges its designs against the surrogate's datum, as the page's
/// surrogate map does).
#[derive(Debug, Clone)]
pub struct MapRequest<'a> {
    /// The LoFi (`quarter`), the HiFi (`full`) or a surrogate of the HiFi.
    pub model: EvaluatorSpec,
    /// A surrogate's HiFi sampling plan (default `ae:10`).
    pub plan: PlanSpec,
    /// The box a surrogate is fitted over, N/m and N s/m (`None`: the grid's). The page
    /// fits over its design box and maps at the cells' centres inside it.
    pub fit_box: Option<DesignBox>,
    /// The datum car (its front spring and damper are the datum design).
    pub car: &'a Car,
    /// The road.
    pub road: &'a Road,
    /// The grid, the scale, the design objectives, the contour levels and the comfort
    /// measure.
    pub settings: MapSettings,
    /// The HiFi fields' path ([`HiFiGrid::compute`]).
    pub compute: Compute,
}

impl<'a> MapRequest<'a> {
    /// The HiFi fields on the CPU: the same report on every machine (`ridelab map` sets
    /// `compute` from `--compute`).
    pub fn new(
        model: impl Into<EvaluatorSpec>,
        car: &'a Car,
        road: &'a Road,
        settings: MapSettings,
    ) -> Self {
        MapRequest {
            model: model.into(),
            plan: PlanSpec::AudzeEglais(10),
            fit_box: None,
            car,
            road,
            settings,
            compute: Compute::Cpu,
        }
    }

    /// Runs it: the HiFi fields on the path `compute` asks for ([`HiFiGrid::compute`]:
    /// `Auto` takes a hardware GPU when there is one, `Compute::Cpu` the CPU); the report's
    /// `compute` says which ran. The LoFi has no GPU path: `Compute::Gpu` with
    /// [`ModelKind::Quarter`] is an error naming `compute`, `Auto` maps on the CPU; the
    /// Wk-weighted comfort is computed on the CPU, `Compute::Gpu` with it an error naming
    /// `comfort`. A grid with a corner outside the car's design domain
    /// ([`crate::car::DesignDomain`]) is an error naming `ks-range` or `cs-range`. A
    /// surrogate is fitted to the HiFi at `plan`'s points over [`Self::surrogate_box`],
    /// then mapped on the CPU ([`Self::run_surrogate`]).
    pub fn run(&self) -> Result<MapReport> {
        let (car, road, settings) = (self.car, self.road, &self.settings);
        settings.grid.design_box().check_on(&car.design_domain())?;
        let kind = match self.model {
            EvaluatorSpec::Model(kind) => kind,
            EvaluatorSpec::Surrogate(_) => return self.run_surrogate(),
        };
        match (kind, self.compute) {
            (ModelKind::Quarter, Compute::Gpu) => Err(RideError::field(
                "compute",
                "gpu: the GPU path maps the full model only (use --compute cpu or auto with the quarter car)",
            )),
            (ModelKind::Quarter, _) => self.run_model_on_cpu(kind),
            // The exact Wk route runs on the CPU (the GPU route has no Wk filter).
            (ModelKind::Full, Compute::Gpu) if settings.comfort == Comfort::Wk => Err(RideError::field(
                "comfort",
                "wk: the Wk-weighted comfort is computed on the CPU (use --compute cpu or auto)",
            )),
            (ModelKind::Full, _) if settings.comfort == Comfort::Wk => self.run_model_on_cpu(kind),
            (ModelKind::Full, _) => {
                settings.validate()?;
                let hifi = HiFiGrid::compute(
                    HiFi::new(car, road)?,
                    &settings.grid,
                    self.compute,
                    default_threads(),
                )?;
                let mut r = self.run_on(&hifi)?;
                r.compute = hifi.path();
                r.adapter = hifi.adapter().map(str::to_string);
                Ok(r)
            }
        }
    }

    /// The map by the request's model `kind` (with `settings.comfort` in the BAcc slot)
    /// on the CPU.
    fn run_model_on_cpu(&self, kind: ModelKind) -> Result<MapReport> {
        let (car, road) = (self.car, self.road);
        car.validate()?;
        road.validate()?;
        match (self.settings.comfort, kind) {
            (Comfort::Bacc, ModelKind::Quarter) => self.run_on(&LoFi::new(car, road)),
            (Comfort::Bacc, ModelKind::Full) => self.run_on(&HiFi::new(car, road)?),
            (comfort, model) => self.run_on(&*comfort.evaluator(model, car, road)?),
        }
    }

    /// The map of the request's surrogate: fitted to the HiFi at `plan`'s points over
    /// [`Self::surrogate_box`] (the HiFi built once), then evaluated at every grid point on
    /// the CPU.
    /// `compute` gpu is an error naming `compute` (a surrogate has no GPU path), and the
    /// Wk-weighted comfort one naming `comfort` (the surrogates are fitted to the
    /// unweighted BAcc).
    fn run_surrogate(&self) -> Result<MapReport> {
        let settings = &self.settings;
        if self.compute == Compute::Gpu {
            return Err(RideError::field(
                "compute",
                "gpu: a surrogate's map is evaluated on the CPU (use --compute cpu or auto)",
            ));
        }
        if settings.comfort == Comfort::Wk {
            return Err(RideError::field("comfort", WK_SURROGATE_MAP));
        }
        settings.validate()?;
        let fit_box = self.surrogate_box()?;
        let model = self.model.build(self.car, self.road, &fit_box, self.plan)?;
        self.run_on(&*model)
    }

    /// The box a surrogate is fitted over: `fit_box`, else the grid's; checked and inside
    /// the car's design domain (errors name `fit-ks-range` or `fit-cs-range`).
    pub(crate) fn surrogate_box(&self) -> Result<DesignBox> {
        let b = self.fit_box.unwrap_or(self.settings.grid.design_box());
        b.validate()
            .and_then(|()| b.check_on(&self.car.design_domain()))
            .map_err(|e| match e {
                RideError::Field { field, reason } => {
                    RideError::field(format!("fit-{field}"), reason)
                }
                other => other,
            })?;
        Ok(b)
    }

    /// The map on `evaluator` (a surrogate, a measured road's model, the HiFi's values on
    /// the grid, say) in place of the request's model, which should model `car` on `road`:
    /// `car` gives the datum design, the DOS context and the report's car name, `road` is
    /// recorded, `settings` as in [`Self::run`]. `model` and `compute` are not read: the
    /// report's evaluator is `evaluator`'s name, its `compute` the CPU (a caller that maps
    /// elsewhere sets it); `settings.comfort` only labels the report (the evaluator gives
    /// the comfort measure it was built with).
    pub fn run_on<E: Evaluator + Sync + ?Sized>(&self, evaluator: &E) -> Result<MapReport> {
        let (car, settings) = (self.car, &self.settings);
        settings.validate()?;
        let abs = Dcs::compute(
            evaluator,
            &settings.grid,
            (car.front.spring, car.front.damper),
            Scale::Absolute,
        )?;
        let ctx = DosContext::new(car, abs.datum.criteria);
        let dos = DosMap::new(&abs, &settings.objectives, &ctx)?;
        self.report_from(&abs, dos)
    }

    /// The map report of absolute criteria `abs` with the feasibility mask `dos` (both over
    /// `settings.grid`): the fields in `settings.scale`, contours and the feasible outline;
    /// `car` names the car, `road` is recorded, `model` and `compute` are not read (the
    /// report's `compute` is the CPU). The robust map builds its own fields and mask and
    /// reports them through this.
    pub(crate) fn report_from(&self, abs: &Dcs, dos: DosMap) -> Result<MapReport> {
        let settings = &self.settings;
        let grid = settings.grid;
        let map = abs.to_scale(settings.scale);
        let lines = |k: usize| -> Result<Vec<Contour>> {
            let f = map.field(k);
            contours(&grid, f, &auto_levels(f, settings.contour_levels))
        };
        let units = match settings.scale {
            Scale::Absolute => Units {
                ks: "N/m",
                cs: "N s/m",
                bacc: "m/s^2",
                dtl: "N",
                sws: "m",
            },
            Scale::Relative => Units {
                ks: "N/m",
                cs: "N s/m",
                bacc: "-",
                dtl: "-",
                sws: "-",
            },
        };
        let contours = CriteriaContours {
            bacc: lines(0)?,
            dtl: lines(1)?,
            sws: lines(2)?,
        };
        let outline = contour(&grid, &dos.feasible_field(), 0.5)?;
        let legend = dos
            .active
            .iter()
            .map(|&o| MaskBit {
                objective: o,
                bit: objective_bit(o),
                label: o.label(),
            })
            .collect();
        Ok(MapReport {
            evaluator: map.evaluator.clone(),
            car: self.car.name.clone(),
            road: RoadScenario::Iso(*self.road),
            scale: settings.scale,
            grid,
            ks_values: grid.ks.values(),
            cs_values: grid.cs.values(),
            layout: LAYOUT,
            units,
            comfort: settings.comfort,
            datum: map.datum,
            feasibility: Feasibility {
                objectives: dos.objectives,
                legend,
                mask: dos.mask,
                summary: dos.summary,
                feasible_set: dos.feasible_set,
                outline,
            },
            contours,
            bacc: map.bacc,
            dtl: map.dtl,
            sws: map.sws,
            compute: ComputePath::Cpu,
            adapter: None,
        })
    }
}

/// The report as CSV, one row per grid point in map order (Cs rows, Ks columns):
/// `ks_n_per_m,cs_ns_per_m,bacc_m_per_s2,dtl_n,sws_m,feasible,broken`, where `broken`
/// lists the broken objectives' names separated by `;`. A relative report names its
/// criteria columns `bacc_ratio,dtl_ratio,sws_ratio`. With Wk comfort the BAcc column is
/// `bacc_wk_m_per_s2` (`bacc_wk_ratio`).
pub fn map_csv(report: &MapReport) -> String {
    let mut out = String::with_capacity(64 * (report.bacc.len() + 1));
    let header = match report.scale {
        Scale::Absolute => "ks_n_per_m,cs_ns_per_m,bacc_m_per_s2,dtl_n,sws_m,feasible,broken\n",
        Scale::Relative => {
            "ks_n_per_m,cs_ns_per_m,bacc_ratio,dtl_ratio,sws_ratio,feasible,broken\n"
        }
    };
    match report.comfort {
        Comfort::Bacc => out.push_str(header),
        Comfort::Wk => out.push_str(&header.replacen("bacc_", "bacc_wk_", 1)),
    }
    let g = report.grid;
    for k in 0..g.len() {
        let (i, j) = g.indices(k);
        let mask = report.feasibility.mask[k];
        let broken: Vec<&str> = objectives_in(mask)
            .into_iter()
            .map(objective_name)
            .collect();
        out.push_str(&format!(
            "{},{},{},{},{},{},{}\n",
            report.ks_values[i],
            report.cs_values[j],
            report.bacc[k],
            report.dtl[k],
            report.sws[k],
            mask == 0,
            broken.join(";")
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::road::RoadClass;

    fn settings(n_ks: usize, n_cs: usize) -> MapSettings {
        MapSettings {
            grid: Grid::over_box(&crate::design::DesignBox::default(), n_ks, n_cs).unwrap(),
            ..MapSettings::default()
        }
    }

    #[test]
    fn quarter_report_json_and_csv() {
        let car = Car::datum();
        let road = Road::default();
        let s = settings(21, 15);
        let r = MapRequest::new(ModelKind::Quarter, &car, &road, s)
            .run()
            .unwrap();
        assert_eq!(r.evaluator, "quarter");
        assert_eq!(r.bacc.len(), 21 * 15);
        assert_eq!(r.datum.ks, car.front.spring);
        let lofi = LoFi {
            car: car.clone(),
            road,
        };
        assert_eq!(
            r.datum.criteria,
            lofi.evaluate(car.front.spring, car.front.damper).unwrap()
        );
        // Class B: the 7 mm SWS limit splits the default box.
        let f = &r.feasibility;
        assert_eq!(f.legend.len(), 1);
        assert!(f.summary.feasible > 0 && f.summary.feasible < r.bacc.len());
        assert!(!f.outline.polylines.is_empty());
        for (k, &m) in f.mask.iter().enumerate() {
            assert_eq!(m == 0, r.sws[k] <= 0.007, "{k}");
        }
        for c in [&r.contours.bacc, &r.contours.dtl, &r.contours.sws] {
            assert!(!c.is_empty() && c.len() <= 10);
            assert!(c.iter().all(|l| !l.polylines.is_empty()));
        }
        let json = serde_json::to_value(&r).unwrap();
        for key in [
            "grid",
            "ks_values",
            "cs_values",
            "units",
            "datum",
            "bacc",
            "dtl",
            "sws",
            "layout",
        ] {
            assert!(json.get(key).is_some(), "{key}");
        }
        assert_eq!(json["feasibility"]["legend"][0]["objective"], "sws_limit");
        assert_eq!(json["units"]["bacc"], "m/s^2");
        assert!(json["contours"]["bacc"][0]["polylines"][0]["points"][0][0].is_f64());

        let csv = map_csv(&r);
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines.len(), 1 + 21 * 15);
        assert_eq!(
            lines[0],
            "ks_n_per_m,cs_ns_per_m,bacc_m_per_s2,dtl_n,sws_m,feasible,broken"
        );
        // Row 1 of the CSV is the lowest Cs at the lowest Ks; row 2 the next Ks.
        let first: Vec<&str> = lines[1].split(',').collect();
        assert_eq!(first[0].parse::<f64>().unwrap(), 10_000.0);
        assert_eq!(first[1].parse::<f64>().unwrap(), 500.0);
        assert_eq!(first[2].parse::<f64>().unwrap(), r.bacc[0]);
        assert_eq!(
            lines[2].split(',').next().unwrap().parse::<f64>().unwrap(),
            11_500.0
        );
        for (k, line) in lines[1..].iter().enumerate() {
            let cols: Vec<&str> = line.split(',').collect();
            assert_eq!(cols.len(), 7);
            assert_eq!(cols[5] == "true", r.feasibility.mask[k] == 0);
            assert_eq!(cols[6] == "sws_limit", r.feasibility.mask[k] != 0);
        }
    }

    #[test]
    fn relative_and_full_reports() {
        let car = Car::datum();
        let road = Road {
            class: RoadClass::C,
            ..Road::default()
        };
        let mut s = settings(5, 4);
        s.scale = Scale::Relative;
        let r = MapRequest::new(ModelKind::Full, &car, &road, s)
            .run()
            .unwrap();
        assert_eq!(r.evaluator, "full");
        assert_eq!(r.units.dtl, "-");
        let hifi = HiFi::new(&car, &road).unwrap();
        let d = r.datum.criteria.to_array();
        for k in 0..r.grid.len() {
            let (i, j) = r.grid.indices(k);
            let c = hifi
                .evaluate(r.ks_values[i], r.cs_values[j])
                .unwrap()
                .to_array();
            assert_eq!(
                [r.bacc[k], r.dtl[k], r.sws[k]],
                [c[0] / d[0], c[1] / d[1], c[2] / d[2]]
            );
        }
        // Class C: nothing meets 7 mm, and the report says so.
        let m = r.feasibility.summary.message.clone().unwrap();
        assert!(m.contains("SWS limit broken at every point"), "{m}");
        assert!(r.feasibility.outline.polylines.is_empty());
        assert!(map_csv(&r).starts_with("ks_n_per_m,cs_ns_per_m,bacc_ratio,"));
    }

    #[test]
    fn bad_settings_name_the_field() {
        let car = Car::datum();
        let mut s = MapSettings::default();
        s.grid.cs.n = 1;
        let e = MapRequest::new(ModelKind::Quarter, &car, &Road::default(), s)
            .run()
            .unwrap_err();
        assert!(e.to_string().starts_with("cs-range: "), "{e}");
        let s = MapSettings {
            contour_levels: 51,
            ..MapSettings::default()
        };
        let e = MapRequest::new(ModelKind::Quarter, &car, &Road::default(), s)
            .run()
            .unwrap_err();
        assert!(e.to_string().starts_with("contour_levels: "), "{e}");
        let s: MapSettings = serde_json::from_str(r#"{"scale": "relative"}"#).unwrap();
        assert_eq!(s.grid, Grid::default());
        assert!(serde_json::from_str::<MapSettings>(r#"{"scal": "relative"}"#).is_err());
    }
}
