//! The robust map (`ridelab map --cases FILE`): every case's criteria over the grid, the
//! robust criteria ([`crate::robust::objective`]) as the map's fields and the robust DOS (the OR
//! of every case's feasibility mask, each case with its own datum) as its mask; or one
//! case's own map (`--case K`).

use crate::analysis::{HiFi, HiFiRoads, ModelKind};
use crate::comfort::Comfort;
use crate::dos::{DesignObjectives, Objective};
use crate::error::{Result, RideError};
use crate::evaluate::Criteria;
use crate::gpu::{ComputePath, HiFiGrid};
use crate::maps::{default_threads, map_grid, DatumPoint, Dcs, DosMap, FeasiblePoint, Grid, Scale};
use crate::road::Road;
use crate::robust::cases::{Case, CaseSet, Combine};
use crate::robust::objective::Combination;
use crate::study::EvaluatorSpec;
use crate::study::{MapReport, MapRequest, MapSettings};
use serde::Serialize;

/// One case as a report lists it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CaseInfo {
    /// Index of the case (load-case-major).
    pub index: usize,
    /// `"<load case> / <class> at <speed> m/s"`.
    pub name: String,
    /// The case's road.
    pub road: Road,
    /// Its weight `w_load w_op`, and `p = w / sum w`.
    pub weight: f64,
    /// Normalised weight, -.
    pub probability: f64,
    /// The loaded car's sprung mass, kg.
    pub sprung_mass: f64,
    /// CG to front axle, m.
    pub a: f64,
    /// CG to rear axle, m.
    pub b: f64,
    /// Pitch inertia, kg m^2.
    pub pitch_inertia: f64,
    /// Roll inertia, kg m^2.
    pub roll_inertia: f64,
    /// Quarter-car sprung mass `M b / (2 L)`, kg.
    pub quarter_mass: f64,
    /// Static front wheel load, N.
    pub static_wheel_load: f64,
    /// The case's datum criteria (the datum design in this case).
    pub datum: Criteria,
}

impl CaseInfo {
    /// The description of case `index` of `set` with datum criteria `datum`.
    pub fn new(set: &CaseSet, index: usize, datum: Criteria) -> CaseInfo {
        let c: &Case = &set.cases[index];
        CaseInfo {
            index,
            name: c.name.clone(),
            road: c.road,
            weight: c.weight,
            probability: set.probabilities()[index],
            sprung_mass: c.car.sprung_mass,
            a: c.car.a,
            b: c.car.b,
            pitch_inertia: c.car.pitch_inertia,
            roll_inertia: c.car.roll_inertia,
            quarter_mass: c.car.quarter().ms,
            static_wheel_load: c.car.front_wheel_load(),
            datum,
        }
    }
}

/// What the robust map adds to a map report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RobustInfo {
    /// Worst case or weighted mean.
    pub combine: Combine,
    /// How the fields are normalised, in words.
    pub normalisation: &'static str,
    /// The cases.
    pub cases: Vec<CaseInfo>,
    /// Per case, the grid points feasible in that case.
    pub feasible_per_case: Vec<usize>,
}

/// The normalisation sentence of robust reports.
pub(crate) const NORMALISATION: &str = "each case scaled to case 0's datum: worst R = max_k (d_0 / d_k) c_k, mean R = sum_k p_k (d_0 / d_k) c_k; feasible only where every case meets every objective against its own datum";

/// A robust map: the map report (robust fields and mask) and the cases.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RobustMapReport {
    /// The map, its fields the robust criteria in case 0's units.
    #[serde(flatten)]
    pub map: MapReport,
    /// The cases and the rule.
    pub robust: RobustInfo,
}

/// One case's own map, with the case it is.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CaseMapReport {
    /// The case's map (its loaded car on its road, its own datum).
    #[serde(flatten)]
    pub map: MapReport,
    /// The case.
    pub case: CaseInfo,
}

/// One case's absolute criteria on the map's grid and its feasibility mask (judged
/// against that case's own datum), as [`robust_fields`] combines them.
#[derive(Debug, Clone, Copy)]
pub(crate) struct CaseField<'a> {
    /// The evaluator's name.
    pub evaluator: &'a str,
    /// The datum design and its criteria in this case.
    pub datum: DatumPoint,
    /// RMS body acceleration (or the comfort measure), m/s^2, grid order.
    pub bacc: &'a [f64],
    /// RMS dynamic tyre load, N.
    pub dtl: &'a [f64],
    /// RMS suspension working space, m.
    pub sws: &'a [f64],
    /// Broken-objective bits per grid point (0: feasible).
    pub mask: &'a [u8],
}

/// The robust map of the cases' fields `cases` (one per case of `set`, in case order, on
/// `grid`): at every point the robust criteria ([`Combination`] of the cases' datums
/// and `set`'s probabilities, in case 0's units) and the robust mask, the OR of the
/// cases' masks (feasible only where every case is). `active` are the objectives of the
/// masks' bits. Returns the absolute fields (datum: case 0's datum design with the
/// robust datum) and the mask with its feasible set.
pub(crate) fn robust_fields(
    set: &CaseSet,
    grid: Grid,
    objectives: &DesignObjectives,
    active: Vec<Objective>,
    cases: &[CaseField],
) -> Result<(Dcs, DosMap)> {
    let datums: Vec<Criteria> = cases.iter().map(|m| m.datum.criteria).collect();
    let combination = Combination::new(set.combine, &datums, &set.probabilities())?;
    let n = grid.len();
    let mut fields = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
    let mut mask = vec![0u8; n];
    let mut per = vec![Criteria::from_array([0.0; 3]); cases.len()];
    for k in 0..n {
        for (c, m) in per.iter_mut().zip(cases) {
            *c = Criteria {
                bacc: m.bacc[k],
                dtl: m.dtl[k],
                sws: m.sws[k],
            };
            mask[k] |= m.mask[k];
        }
        let r = combination.apply(&per).to_array();
        for j in 0..3 {
            fields[j][k] = r[j];
        }
    }
    let [bacc, dtl, sws] = fields;
    let feasible_set = (0..n)
        .filter(|&k| mask[k] == 0)
        .map(|k| {
            let (i, j) = grid.indices(k);
            let (ks, cs) = grid.point(i, j);
            FeasiblePoint {
                ks,
                cs,
                bacc: bacc[k],
                dtl: dtl[k],
                sws: sws[k],
            }
        })
        .collect();
    let dos = DosMap::from_mask(grid, objectives, active, mask, feasible_set);
    let first = &cases[0];
    let abs = Dcs {
        evaluator: if cases.len() == 1 {
            first.evaluator.to_string()
        } else {
            format!("{} x {} cases", first.evaluator, cases.len())
        },
        grid,
        scale: Scale::Absolute,
        datum: DatumPoint {
            ks: first.datum.ks,
            cs: first.datum.cs,
            criteria: combination.datum,
        },
        bacc,
        dtl,
        sws,
    };
    Ok((abs, dos))
}

impl MapRequest<'_> {
    /// The map of case `index` of `set` alone, as [`Self::run`] maps that case's loaded
    /// car on its road (its own datum) with the request's model, settings and path: the
    /// request's `car` and `road` are not read (the case brings them). An index past the
    /// cases is an error naming `case`.
    pub fn run_case(&self, set: &CaseSet, index: usize) -> Result<CaseMapReport> {
        let case = set.cases.get(index).ok_or_else(|| {
            RideError::field(
                "case",
                format!(
                    "{index} is not a case: there are {} (0..{})",
                    set.cases.len(),
                    set.cases.len() - 1
                ),
            )
        })?;
        let map = MapRequest {
            car: &case.car,
            road: &case.road,
            ..self.clone()
        }
        .run()?;
        let info = CaseInfo::new(set, index, map.datum.criteria);
        Ok(CaseMapReport { map, case: info })
    }

    /// The robust map of `set` (built from the request's car and road: each case brings
    /// its loaded car and its road): each case's map by the request's model on its path,
    /// as [`Self::run`] (see [`case_maps`]), combined by the set's rule into the robust
    /// fields and mask, reported in `settings.scale` with contours. The request's `car`
    /// names the report and gives the datum design (the front spring and damper every case
    /// shares), `road` is recorded. More grid points over all the cases than the run
    /// budget ([`crate::budget::check`]) is an error naming `ks-range`.
    pub fn run_robust(&self, set: &CaseSet) -> Result<RobustMapReport> {
        let settings = &self.settings;
        settings.validate()?;
        let (nx, ny) = (settings.grid.ks.n, settings.grid.cs.n);
        crate::budget::check(
            (nx as u64) * (ny as u64) * set.cases.len() as u64,
            "ks-range",
            &format!("a {nx} x {ny} map over {} cases", set.cases.len()),
            "the points of --ks-range and --cs-range, or the cases",
        )?;
        // Each case's absolute fields and mask, without its own contours.
        let per_case = MapRequest {
            settings: MapSettings {
                scale: Scale::Absolute,
                contour_levels: 0,
                ..settings.clone()
            },
            ..self.clone()
        };
        let maps = case_maps(&per_case, set)?;
        let fields: Vec<CaseField> = maps
            .iter()
            .map(|m| CaseField {
                evaluator: &m.evaluator,
                datum: m.datum,
                bacc: &m.bacc,
                dtl: &m.dtl,
                sws: &m.sws,
                mask: &m.feasibility.mask,
            })
            .collect();
        let active = maps[0]
            .feasibility
            .legend
            .iter()
            .map(|b| b.objective)
            .collect();
        let (abs, dos) = robust_fields(set, settings.grid, &settings.objectives, active, &fields)?;
        let datums: Vec<Criteria> = maps.iter().map(|m| m.datum.criteria).collect();
        let first = &maps[0];
        let mut map = self.report_from(&abs, dos)?;
        map.compute = first.compute;
        map.adapter = first.adapter.clone();
        let robust = RobustInfo {
            combine: set.combine,
            normalisation: NORMALISATION,
            cases: datums
                .iter()
                .enumerate()
                .map(|(k, d)| CaseInfo::new(set, k, *d))
                .collect(),
            feasible_per_case: maps
                .iter()
                .map(|m| m.feasibility.summary.feasible)
                .collect(),
        };
        Ok(RobustMapReport { map, robust })
    }
}

/// Every case's map report as [`MapRequest::run`] gives it for `request` on that case's
/// loaded car and road (`request`'s settings as the robust map sets them), in case order.
/// On the HiFi's CPU path (unweighted BAcc) the cases of one loaded car
/// ([`CaseSet::car_runs`]) are mapped together by one [`HiFiRoads`]: the same values bit
/// for bit, the road-independent work done once a grid point (for 2 load cases x 3 speeds
/// about 2 single maps' work instead of 6). Cases the GPU maps stay on it; where anything
/// fails, the run's cases are mapped one by one, so errors are those of
/// [`MapRequest::run`] too.
fn case_maps(request: &MapRequest, set: &CaseSet) -> Result<Vec<MapReport>> {
    let one = |c: &Case| {
        MapRequest {
            car: &c.car,
            road: &c.road,
            ..request.clone()
        }
        .run()
    };
    let settings = &request.settings;
    if request.model != EvaluatorSpec::Model(ModelKind::Full) || settings.comfort != Comfort::Bacc {
        return set.cases.iter().map(one).collect();
    }
    settings.validate()?;
    let mut maps = Vec::with_capacity(set.cases.len());
    for run in set.car_runs() {
        let cases = &set.cases[run];
        match shared_maps(request, cases) {
            Some(m) => maps.extend(m),
            None => {
                for c in cases {
                    maps.push(one(c)?);
                }
            }
        }
    }
    Ok(maps)
}

/// The maps of `cases` (one loaded car) by `request`'s settings: each on the GPU where
/// [`HiFiGrid::on_gpu`] takes it (on `request`'s path), the others by one [`HiFiRoads`]
/// over the grid; `None` where anything fails.
fn shared_maps(request: &MapRequest, cases: &[Case]) -> Option<Vec<MapReport>> {
    let grid = &request.settings.grid;
    let mut hifis: Vec<Option<HiFiGrid>> = Vec::with_capacity(cases.len());
    for c in cases {
        let hifi = HiFi::new(&c.car, &c.road).ok()?;
        hifis.push(HiFiGrid::on_gpu(&hifi, grid, request.compute).ok()?);
    }
    let cpu: Vec<usize> = (0..cases.len()).filter(|&k| hifis[k].is_none()).collect();
    if !cpu.is_empty() {
        let roads: Vec<Road> = cpu.iter().map(|&k| cases[k].road).collect();
        let many = HiFiRoads::new(&cases[0].car, &roads).ok()?;
        let values = map_grid(grid, default_threads(), Vec::new(), |ks, cs| {
            many.evaluate(ks, cs)
        })
        .ok()?;
        for (r, &k) in cpu.iter().enumerate() {
            let v = values.iter().map(|p| p[r]).collect();
            let hifi = many.hifis()[r].clone();
            hifis[k] = Some(HiFiGrid::from_values(hifi, *grid, v, ComputePath::Cpu));
        }
    }
    cases
        .iter()
        .zip(hifis)
        .map(|(c, h)| {
            let h = h?;
            let mut r = MapRequest {
                car: &c.car,
                road: &c.road,
                ..request.clone()
            }
            .run_on(&h)
            .ok()?;
            r.compute = h.path();
            r.adapter = h.adapter().map(str::to_string);
            Some(r)
        })
        .collect()
}
