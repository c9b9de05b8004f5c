//! The LoFi and HiFi evaluators over the design variables, and the full analysis
//! report of one design (criteria by both routes, modes, ride properties).

use crate::car::{Car, DesignDomain, QuarterCar};
use crate::criteria::{
    bacc_wk, bacc_wk_spectral, comfort_label, criteria_exact, criteria_fast_exact, criteria_modal,
    criteria_spectral, quarter_car_rms, Certified, ResidueFamily, ResidueRoads, ResidueRoute,
};
use crate::error::{parse_choice, Result, RideError};
use crate::evaluate::{Criteria, Evaluator};
use crate::model::Mode;
use crate::model::{antisymmetric_half, full_car, quarter_car, symmetric_half, LinearModel};
use crate::road::{Road, RoadScenario, Tracks};
use serde::{Deserialize, Serialize};
use std::sync::atomic::{AtomicU64, Ordering};
use strum::{EnumIter, EnumProperty, IntoStaticStr, VariantNames};

/// Which vehicle model: parses "quarter" (or "lofi") and "full" (or "hifi") in any case;
/// errors name `model`.
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    Serialize,
    Deserialize,
    EnumIter,
    EnumProperty,
    IntoStaticStr,
    VariantNames,
)]
#[serde(rename_all = "lowercase")]
pub enum ModelKind {
    /// LoFi: 2-DOF quarter car of the front corner.
    #[strum(serialize = "quarter", props(alias = "lofi"))]
    Quarter,
    /// HiFi: 7-DOF full car.
    #[strum(serialize = "full", props(alias = "hifi"))]
    Full,
}

impl std::str::FromStr for ModelKind {
    type Err = RideError;
    fn from_str(s: &str) -> Result<ModelKind> {
        ModelKind::parse(s)
    }
}

impl ModelKind {
    /// Parses "quarter" or "full" (surrounding blanks ignored).
    pub fn parse(s: &str) -> Result<ModelKind> {
        parse_choice("model", s)
    }

    /// The linear model of `car` for this kind.
    pub fn build(self, car: &Car) -> LinearModel {
        match self {
            ModelKind::Quarter => quarter_car(&car.quarter()),
            ModelKind::Full => full_car(car),
        }
    }
}

/// LoFi evaluator: the front quarter car of `car` on `road` with the front spring and
/// damper replaced. Closed forms for an undamped tyre, the exact Lyapunov route otherwise.
#[derive(Debug, Clone, PartialEq)]
pub struct LoFi {
    /// The car (rear and masses fixed).
    pub car: Car,
    /// The road.
    pub road: Road,
}

impl LoFi {
    /// The LoFi evaluator of `car` on `road`.
    pub fn new(car: &Car, road: &Road) -> LoFi {
        LoFi {
            car: car.clone(),
            road: *road,
        }
    }
}

/// LoFi criteria of any quarter car on `road`: the closed forms for an undamped tyre,
/// the exact Lyapunov route otherwise.
pub fn quarter_criteria(q: &QuarterCar, road: &Road) -> Result<Criteria> {
    q.validate()?;
    if q.ct == 0.0 {
        Ok(quarter_car_rms(q, road.intensity()))
    } else {
        criteria_exact(&quarter_car(q), road)
    }
}

/// `car`'s front quarter car with the front spring `ks` (N/m) and damper `cs` (N s/m):
/// the car's own faults first (they name its field), then the design's domain.
pub(crate) fn front_quarter(car: &Car, ks: f64, cs: f64) -> Result<QuarterCar> {
    let mut q = car.quarter();
    q.ks = ks;
    q.cs = cs;
    q.validate()?;
    DesignDomain::new(q.ms, q.kt).check(ks, cs)?;
    Ok(q)
}

impl Evaluator for LoFi {
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
        quarter_criteria(&front_quarter(&self.car, ks, cs)?, &self.road)
    }
    fn name(&self) -> String {
        "quarter".into()
    }
}

/// Which route gave a HiFi value.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum HiFiRoute {
    /// The residue route ([`crate::criteria::ResidueRoute`]): its error bound held.
    Residue,
    /// The modal route ([`criteria_modal`]): a fallback, or the reference evaluator's route.
    Modal,
    /// The Kronecker Lyapunov route ([`criteria_exact`]), where the modal route declines.
    Kronecker,
    /// The frequency route with ISO 8608's low cutoff, on a road warp.
    Spectral,
}

/// How many points each route has given since a [`HiFi`] was made.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct RouteCounts {
    /// Points by the residue route.
    pub residue: u64,
    /// Points by the modal route.
    pub modal: u64,
    /// Points by the Kronecker route.
    pub kronecker: u64,
    /// Points by the frequency route (road warp).
    pub spectral: u64,
}

impl RouteCounts {
    /// Points not given by the residue route (its fallbacks, or every point of the
    /// reference evaluator).
    pub fn others(&self) -> u64 {
        self.modal + self.kronecker + self.spectral
    }
}

/// HiFi evaluators prepared in this process (valid cars and roads; clones not counted).
static HIFI_BUILDS: AtomicU64 = AtomicU64::new(0);

/// How many HiFi evaluators this process has prepared ([`HiFi::new`] and
/// [`HiFi::with_modal_route`] with a valid car and road): a run's count is the difference
/// across it (`tests/hifi_builds.rs`: one per `ridelab optimize --evaluator full`).
pub fn hifi_builds() -> u64 {
    HIFI_BUILDS.load(Ordering::Relaxed)
}

/// Thread-safe route counters of a [`HiFi`]: bookkeeping, not part of its value (clones
/// copy the counts, and any two tallies compare equal).
#[derive(Debug, Default)]
struct Tally([AtomicU64; 4]);

impl Tally {
    fn add(&self, route: HiFiRoute) {
        self.0[route as usize].fetch_add(1, Ordering::Relaxed);
    }

    fn counts(&self) -> RouteCounts {
        let n = |r: HiFiRoute| self.0[r as usize].load(Ordering::Relaxed);
        RouteCounts {
            residue: n(HiFiRoute::Residue),
            modal: n(HiFiRoute::Modal),
            kronecker: n(HiFiRoute::Kronecker),
            spectral: n(HiFiRoute::Spectral),
        }
    }
}

impl Clone for Tally {
    fn clone(&self) -> Self {
        Tally(std::array::from_fn(|i| {
            AtomicU64::new(self.0[i].load(Ordering::Relaxed))
        }))
    }
}

impl PartialEq for Tally {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

/// HiFi evaluator: the full car with both front corners set to `(ks, cs)`.
///
/// Each point goes by the residue route ([`crate::criteria::ResidueRoute`], a few
/// microseconds) when its first-order error bound is within
/// [`crate::criteria::RESIDUE_TOLERANCE`], and otherwise by the exact modal route with
/// the Kronecker route behind it (a road warp goes to the frequency route); which route
/// gave a point is returned by [`HiFi::evaluate_routed`] and counted in
/// [`HiFi::route_counts`]. With correlated tracks the model is the left-right symmetric
/// half (8 states, exact for mirror-symmetric cars); with independent tracks the residue
/// route sums the symmetric and antisymmetric halves and the fallbacks use the full car.
/// [`HiFi::with_modal_route`] makes the reference evaluator without the residue route.
///
/// The model is affine in the design: `K = K0 + ks dK`, `C = C0 + cs dK`, `dK` the front
/// suspension's (built from the front spring alone, so it carries no rounding from a
/// difference), so it is assembled once and each fallback only adds two scaled matrices.
#[derive(Debug, Clone, PartialEq)]
pub struct HiFi {
    car: Car,
    domain: DesignDomain,
    road: Road,
    base: LinearModel,
    dk: nalgebra::DMatrix<f64>,
    dc: nalgebra::DMatrix<f64>,
    residue: Option<ResidueRoute>,
    tally: Tally,
}

impl HiFi {
    /// Prepares the HiFi evaluator of `car` on `road`, with the residue route where it
    /// applies (every car on correlated tracks, and on independent tracks unless the
    /// track widths differ: a road warp).
    pub fn new(car: &Car, road: &Road) -> Result<HiFi> {
        let mut h = HiFi::with_modal_route(car, road)?;
        h.residue = residue_route(car, road).ok();
        Ok(h)
    }

    /// The reference HiFi evaluator: every point by the modal route (Kronecker behind it).
    pub fn with_modal_route(car: &Car, road: &Road) -> Result<HiFi> {
        car.validate()?;
        road.validate()?;
        HIFI_BUILDS.fetch_add(1, Ordering::Relaxed);
        let (free, unit) = front_family(car);
        let project = |m: &LinearModel| match road.tracks {
            Tracks::Correlated => symmetric_half(m),
            Tracks::Independent => m.clone(),
        };
        let base = project(&full_car(&free));
        let unit = project(&full_car(&unit));
        Ok(HiFi {
            car: car.clone(),
            domain: car.design_domain(),
            road: *road,
            dk: unit.k,
            dc: unit.c,
            base,
            residue: None,
            tally: Tally::default(),
        })
    }

    /// The car.
    pub fn car(&self) -> &Car {
        &self.car
    }

    /// The road.
    pub fn road(&self) -> &Road {
        &self.road
    }

    /// Whether points go by the residue route first.
    pub fn has_residue_route(&self) -> bool {
        self.residue.is_some()
    }

    /// Points given by each route so far (all threads).
    pub fn route_counts(&self) -> RouteCounts {
        self.tally.counts()
    }

    /// The linear model at design `(ks, cs)`: the symmetric half on correlated tracks,
    /// the full car on independent tracks (the model of the exact fallback routes).
    pub(crate) fn model_at(&self, ks: f64, cs: f64) -> LinearModel {
        let mut m = self.base.clone();
        m.k += ks * &self.dk;
        m.c += cs * &self.dc;
        m
    }

    /// The criteria at `(ks, cs)` (N/m, N s/m), the route that gave them and, for the
    /// residue route, its error bound; counted in [`HiFi::route_counts`].
    pub fn evaluate_routed(&self, ks: f64, cs: f64) -> Result<Routed> {
        // The rest of the car was checked in `new`; a valid design needs no more than
        // these comparisons, and the design check (which formats the field) names a fault.
        self.check_point(ks, cs)?;
        let routed = self.route(ks, cs)?;
        self.tally.add(routed.route);
        Ok(routed)
    }

    fn route(&self, ks: f64, cs: f64) -> Result<Routed> {
        if let Some(r) = &self.residue {
            if let Some(routed) = certified(r.criteria(ks, cs)) {
                return Ok(routed);
            }
        }
        self.exact_route(ks, cs)
    }

    /// The exact routes at `(ks, cs)`: modal, Kronecker where it declines, the frequency
    /// route on a road warp.
    fn exact_route(&self, ks: f64, cs: f64) -> Result<Routed> {
        let by = |criteria: Criteria, route: HiFiRoute| Routed {
            criteria,
            route,
            bound: None,
        };
        let mut m = self.base.clone();
        m.k += ks * &self.dk;
        m.c += cs * &self.dc;
        let exact = match criteria_modal(&m, &self.road) {
            Err(RideError::ModalInapplicable(_)) => {
                criteria_exact(&m, &self.road).map(|c| by(c, HiFiRoute::Kronecker))
            }
            other => other.map(|c| by(c, HiFiRoute::Modal)),
        };
        match exact {
            // A road warp: the frequency route with ISO 8608's low cutoff.
            Err(RideError::RoadWarp(_)) => Ok(by(
                criteria_spectral(&m, &self.road, 1e-8)?.criteria,
                HiFiRoute::Spectral,
            )),
            other => other,
        }
    }
}

impl HiFi {
    /// The design check of a point ([`DesignDomain`]): a valid design needs only a few
    /// comparisons, and the check (which formats the field) names a fault.
    fn check_point(&self, ks: f64, cs: f64) -> Result<()> {
        if !self.domain.contains(ks, cs) {
            self.domain.check(ks, cs)?;
        }
        Ok(())
    }
}

/// The residue route's value when it certified one. Anything it cannot certify (or
/// refuses) goes to the exact routes, which give the value or the verdict.
fn certified(residue: Result<Certified>) -> Option<Routed> {
    match residue {
        Ok(Certified::Exact { criteria, bound }) => Some(Routed {
            criteria,
            route: HiFiRoute::Residue,
            bound: Some(bound),
        }),
        _ => None,
    }
}

/// The HiFi of one car on several roads (issue #16: one loaded car at several operating
/// points), each road's criteria equal to its own [`HiFi`]'s bit for bit.
///
/// What is shared: on each road the residue route's model family is the car's alone,
/// and the road enters only through the wheel delays `L / v` and the white road
/// velocity's intensity `W = 2 pi^2 Gd(n0) n0^2 v` (ISO 8608 class and speed). So at
/// each design the roots of the characteristic polynomial, the residues and the
/// static gains are computed once for all roads, the delay terms once per speed (the
/// class only scales `W`), and each road's variances from its own `W` and delays
/// ([`ResidueRoads`]): the same operations on the same operands as each road's own
/// residue route, hence the same bits. Where a road's residue route does not certify a
/// point (its error bound, or a weakly damped pair of roots), that road alone takes its
/// own [`HiFi`]'s exact routes (modal, Kronecker, frequency). Without a residue route
/// (a road warp), or when the roads' families are not of one model (roads with
/// different tracks), every road is evaluated by its own [`HiFi`]. Route counts go to
/// each road's [`HiFi::route_counts`].
#[derive(Debug, Clone, PartialEq)]
pub struct HiFiRoads {
    hifis: Vec<HiFi>,
    shared: Option<ResidueRoads>,
}

impl HiFiRoads {
    /// The HiFi of `car` on each of `roads` (errors as [`HiFi::new`]; at least one road,
    /// else an error naming `roads`).
    pub fn new(car: &Car, roads: &[Road]) -> Result<HiFiRoads> {
        if roads.is_empty() {
            return Err(RideError::field("roads", "needs at least one road"));
        }
        let hifis: Vec<HiFi> = roads
            .iter()
            .map(|r| HiFi::new(car, r))
            .collect::<Result<_>>()?;
        let routes: Option<Vec<ResidueRoute>> = hifis.iter().map(|h| h.residue.clone()).collect();
        let shared = routes.and_then(|r| ResidueRoads::new(r).ok());
        Ok(HiFiRoads { hifis, shared })
    }

    /// Each road's HiFi, in road order.
    pub fn hifis(&self) -> &[HiFi] {
        &self.hifis
    }

    /// Whether the roads share the residue route's road-independent work.
    pub fn is_shared(&self) -> bool {
        self.shared.is_some()
    }

    /// Per road, what its [`HiFi::evaluate_routed`] gives at `(ks, cs)` (N/m, N s/m).
    pub fn evaluate_routed(&self, ks: f64, cs: f64) -> Vec<Result<Routed>> {
        if let Err(e) = self.hifis[0].check_point(ks, cs) {
            return vec![Err(e); self.hifis.len()];
        }
        let residue = self.shared.as_ref().map(|s| s.criteria(ks, cs));
        let mut residue = residue.map(Vec::into_iter);
        self.hifis
            .iter()
            .map(|h| {
                let routed = match residue.as_mut().and_then(Iterator::next) {
                    Some(r) => match certified(r) {
                        Some(routed) => routed,
                        None => h.exact_route(ks, cs)?,
                    },
                    None => h.route(ks, cs)?,
                };
                h.tally.add(routed.route);
                Ok(routed)
            })
            .collect()
    }

    /// Every road's criteria at `(ks, cs)` in road order, or the first road's error.
    pub fn evaluate(&self, ks: f64, cs: f64) -> Result<Vec<Criteria>> {
        self.evaluate_routed(ks, cs)
            .into_iter()
            .map(|r| r.map(|r| r.criteria))
            .collect()
    }
}

/// A HiFi value with the route that gave it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Routed {
    /// The criteria.
    pub criteria: Criteria,
    /// The route.
    pub route: HiFiRoute,
    /// For the residue route, the bound on the relative error of the variances (the
    /// criteria's relative error is half of it).
    pub bound: Option<f64>,
}

/// The car with the front spring and damper set to zero, and the car that has only a
/// unit front spring and damper (no masses, rear suspension or tyres): the full-car
/// matrices of the second are exactly `dK` and `dC` of the front design.
fn front_family(car: &Car) -> (Car, Car) {
    let mut free = car.clone();
    free.front.spring = 0.0;
    free.front.damper = 0.0;
    let bare_axle = crate::car::Axle {
        unsprung_mass: 0.0,
        spring: 0.0,
        damper: 0.0,
        tire_stiffness: 0.0,
        tire_damping: 0.0,
    };
    let mut unit = car.clone();
    unit.sprung_mass = 0.0;
    unit.pitch_inertia = 0.0;
    unit.roll_inertia = 0.0;
    unit.front = crate::car::Axle {
        spring: 1.0,
        damper: 1.0,
        ..bare_axle
    };
    unit.rear = bare_axle;
    (free, unit)
}

/// The residue route of `car` on `road`: the symmetric half on correlated tracks; both
/// halves with weights 1/2 on independent tracks (module doc of
/// [`crate::model::antisymmetric_half`]), each half driven as one source.
fn residue_route(car: &Car, road: &Road) -> Result<ResidueRoute> {
    let symmetric = half_family(car, road, Half::Symmetric)?;
    match road.tracks {
        Tracks::Correlated => ResidueRoute::new(vec![(symmetric, 1.0)]),
        Tracks::Independent => ResidueRoute::new(vec![
            (symmetric, 0.5),
            (half_family(car, road, Half::Antisymmetric)?, 0.5),
        ]),
    }
}

/// One half of a mirror-symmetric full car ([`symmetric_half`], [`antisymmetric_half`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Half {
    /// Heave, pitch and the wheels moving together: driven by the tracks' mean.
    Symmetric,
    /// Roll and the wheels moving against each other: driven by the tracks' half
    /// difference.
    Antisymmetric,
}

/// The residue family of `half` of `car`'s full car over the front design, driven as one
/// source at `road`'s speed and intensity (its tracks setting is not used), started from
/// the car's own design.
pub(crate) fn half_family(car: &Car, road: &Road, half: Half) -> Result<ResidueFamily> {
    let one_source = Road {
        tracks: Tracks::Correlated,
        ..*road
    };
    let (free, unit) = front_family(car);
    let project = match half {
        Half::Symmetric => symmetric_half,
        Half::Antisymmetric => antisymmetric_half,
    };
    let u = project(&full_car(&unit));
    ResidueFamily::new(
        &project(&full_car(&free)),
        &u.k,
        &u.c,
        &one_source,
        (car.front.spring, car.front.damper),
    )
}

impl Evaluator for HiFi {
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
        self.evaluate_routed(ks, cs).map(|r| r.criteria)
    }
    fn name(&self) -> String {
        "full".into()
    }
}

/// Everything `ridelab eval` reports about one design.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Model kind.
    pub model: ModelKind,
    /// Car name.
    pub car: String,
    /// The road: an ISO 8608 class (JSON as [`Road`]) or a measured profile.
    pub road: RoadScenario,
    /// Front spring rate, N/m.
    pub ks: f64,
    /// Front damper rate, N s/m.
    pub cs: f64,
    /// RMS body acceleration above the front wheel, m/s^2.
    pub bacc: f64,
    /// RMS dynamic tyre load, N.
    pub dtl: f64,
    /// RMS suspension working space, m.
    pub sws: f64,
    /// ISO 2631-1 Wk-weighted RMS body acceleration above the front wheel, m/s^2, by the
    /// frequency route to 1e-9 (the exact route, the Wk filter appended to the model,
    /// agrees to 1e-8 but costs a 22-state Lyapunov solve: 50 ms a design in the page).
    pub bacc_wk: f64,
    /// ISO 2631-1 Annex C's likely comfort reaction to `bacc_wk`.
    pub comfort: &'static str,
    /// RMS DTL relative to the static front wheel load, -.
    pub dtl_relative: f64,
    /// Which route gave `bacc`, `dtl`, `sws`: "exact" or "spectral".
    pub route: &'static str,
    /// The frequency route's values, for comparison (always on an ISO road; left out of
    /// the JSON where the check was not made: a slider step on a measured road).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spectral: Option<Criteria>,
    /// Largest relative difference between the exact and the frequency route; `None`
    /// (left out of the JSON) when the frequency route is the only one (road warp), so
    /// that nothing reads as a check that was not made.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub route_difference: Option<f64>,
    /// The frequency route's own error estimate relative to the variance (at most its
    /// tolerance 1e-8 unless its panel splits ran out, as for some road warps); left out
    /// with `spectral`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spectral_error_estimate: Option<f64>,
    /// Lower band limit, Hz, when the response needs ISO 8608's low cutoff (road warp).
    pub low_cutoff_hz: Option<f64>,
    /// Natural frequencies and damping ratios.
    pub modes: Vec<Mode>,
    /// Front body-bounce frequency on the ride rate, Hz.
    pub body_bounce_hz: f64,
    /// Front critical damping `2 sqrt(ks ms)`, N s/m.
    pub critical_damping: f64,
    /// Front damping ratio `cs / (2 sqrt(ks ms))`, -.
    pub damping_ratio: f64,
    /// Front wheel (ride) rate `Kw = ks kt / (ks + kt)`, N/m.
    pub wheel_rate: f64,
    /// Static front wheel load, N.
    pub static_wheel_load: f64,
}

/// Analyses one design of `car` (front spring and damper as in the car) on `road`.
pub fn report(kind: ModelKind, car: &Car, road: &Road) -> Result<Report> {
    car.validate()?;
    road.validate()?;
    let model = kind.build(car);
    let spectral = criteria_spectral(&model, road, 1e-8)?;
    let (values, route) = match criteria_fast_exact(&model, road) {
        Ok(c) => (c, "exact"),
        Err(RideError::RoadWarp(_)) if spectral.low_cutoff_hz.is_some() => {
            (spectral.criteria, "spectral")
        }
        Err(e) => return Err(e),
    };
    let diff = values
        .to_array()
        .iter()
        .zip(spectral.criteria.to_array())
        .map(|(a, b)| (a / b - 1.0).abs())
        .fold(0.0, f64::max);
    let bacc_wk = bacc_wk_spectral(&model, road, 1e-9)?;
    let q = car.quarter();
    Ok(Report {
        model: kind,
        car: car.name.clone(),
        road: RoadScenario::Iso(*road),
        ks: q.ks,
        cs: q.cs,
        bacc: values.bacc,
        dtl: values.dtl,
        sws: values.sws,
        bacc_wk,
        comfort: comfort_label(bacc_wk),
        dtl_relative: values.dtl / car.front_wheel_load(),
        route,
        spectral: Some(spectral.criteria),
        route_difference: (route == "exact").then_some(diff),
        spectral_error_estimate: Some(spectral.relative_error),
        low_cutoff_hz: spectral.low_cutoff_hz,
        modes: model.modes()?,
        body_bounce_hz: q.bounce_frequency(),
        critical_damping: q.critical_damping(),
        damping_ratio: crate::car::damping_ratio(q.ks, q.cs, q.ms),
        wheel_rate: q.wheel_rate(),
        static_wheel_load: car.front_wheel_load(),
    })
}

/// What the page's readout shows of one design while a slider moves: [`Report`]'s
/// criteria, modes and ride properties without its second route. `bacc`, `dtl`, `sws` are
/// the report's own (the exact route; the frequency route where a road warp needs ISO
/// 8608's low cutoff), `bacc_wk` is exact by the modal route ([`bacc_wk`], where the report
/// integrates the frequency route to 1e-9). The report's adaptive quadratures are most of
/// its time (about 1.8 of 1.9 ms for the full car in the page); the page asks for the
/// full report once the design has settled.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Readout {
    /// Model kind.
    pub model: ModelKind,
    /// Front spring rate, N/m.
    pub ks: f64,
    /// Front damper rate, N s/m.
    pub cs: f64,
    /// RMS body acceleration above the front wheel, m/s^2.
    pub bacc: f64,
    /// RMS dynamic tyre load, N.
    pub dtl: f64,
    /// RMS suspension working space, m.
    pub sws: f64,
    /// ISO 2631-1 Wk-weighted RMS body acceleration above the front wheel, m/s^2.
    pub bacc_wk: f64,
    /// ISO 2631-1 Annex C's likely comfort reaction to `bacc_wk`.
    pub comfort: &'static str,
    /// RMS DTL relative to the static front wheel load, -.
    pub dtl_relative: f64,
    /// Which route gave `bacc`, `dtl`, `sws`: "exact" or "spectral".
    pub route: &'static str,
    /// Lower band limit, Hz, when the response needs ISO 8608's low cutoff (road warp).
    pub low_cutoff_hz: Option<f64>,
    /// Natural frequencies and damping ratios.
    pub modes: Vec<Mode>,
    /// Front body-bounce frequency on the ride rate, Hz.
    pub body_bounce_hz: f64,
    /// Front critical damping `2 sqrt(ks ms)`, N s/m.
    pub critical_damping: f64,
    /// Front damping ratio `cs / (2 sqrt(ks ms))`, -.
    pub damping_ratio: f64,
    /// Front wheel (ride) rate `Kw = ks kt / (ks + kt)`, N/m.
    pub wheel_rate: f64,
    /// Static front wheel load, N.
    pub static_wheel_load: f64,
}

/// The readout of one design of `car` on `road` (see [`Readout`]).
pub fn readout(kind: ModelKind, car: &Car, road: &Road) -> Result<Readout> {
    car.validate()?;
    road.validate()?;
    let model = kind.build(car);
    let (values, route, low_cutoff_hz) = match criteria_fast_exact(&model, road) {
        Ok(c) => (c, "exact", None),
        Err(RideError::RoadWarp(why)) => {
            let s = criteria_spectral(&model, road, 1e-8)?;
            match s.low_cutoff_hz {
                Some(f) => (s.criteria, "spectral", Some(f)),
                None => return Err(RideError::RoadWarp(why)),
            }
        }
        Err(e) => return Err(e),
    };
    let wk = bacc_wk(&model, road)?;
    Readout::of(kind, car, values, wk, route, low_cutoff_hz)
}

impl Readout {
    /// The readout of `car`'s design by `kind` with the criteria `values` (m/s^2, N, m)
    /// and the Wk-weighted BAcc `wk` (m/s^2) that `route` gave (`low_cutoff_hz`: its band's
    /// lower limit, Hz, where a road warp needs one), with the modes and ride properties
    /// of the design, which do not depend on the road.
    pub fn of(
        kind: ModelKind,
        car: &Car,
        values: Criteria,
        wk: f64,
        route: &'static str,
        low_cutoff_hz: Option<f64>,
    ) -> Result<Readout> {
        let q = car.quarter();
        Ok(Readout {
            model: kind,
            ks: q.ks,
            cs: q.cs,
            bacc: values.bacc,
            dtl: values.dtl,
            sws: values.sws,
            bacc_wk: wk,
            comfort: comfort_label(wk),
            dtl_relative: values.dtl / car.front_wheel_load(),
            route,
            low_cutoff_hz,
            modes: kind.build(car).modes()?,
            body_bounce_hz: q.bounce_frequency(),
            critical_damping: q.critical_damping(),
            damping_ratio: crate::car::damping_ratio(q.ks, q.cs, q.ms),
            wheel_rate: q.wheel_rate(),
            static_wheel_load: car.front_wheel_load(),
        })
    }
}
