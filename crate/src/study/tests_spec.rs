//! [`StudySpec`]'s map and front: the one pipeline for the road and the cases, and the
//! combinations a study refuses by name.

use super::adaptive::AdaptiveOptions;
use super::model::EvaluatorSpec;
use super::spec::*;
use crate::analysis::ModelKind;
use crate::car::Car;
use crate::error::RideError;
use crate::evaluate::Evaluator;
use crate::gpu::Compute;
use crate::maps::Axis;
use crate::maps::{Grid, Scale};
use crate::optimize::StmParams;
use crate::optimize::{Method, PickRule};
use crate::road::Road;
use crate::road_profile::{MeasuredModel, Profile, ProfileTracks};
use crate::robust::{CaseSet, Combine};
use crate::surrogate::PlanSpec;
use crate::surrogate::SurrogateSpec;

fn grid(n: usize) -> Grid {
    Grid::new(
        Axis {
            min: 12_000.0,
            max: 36_000.0,
            n,
        },
        Axis {
            min: 800.0,
            max: 3_600.0,
            n,
        },
    )
    .unwrap()
}

fn ask(model: ModelKind, case: Option<usize>) -> MapAsk {
    MapAsk {
        model: model.into(),
        plan: PlanSpec::AudzeEglais(10),
        grid: grid(4),
        scale: Scale::Absolute,
        case,
    }
}

fn slab() -> StudySpec {
    let file = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../assets/roads/concrete-slab-5m.csv"
    );
    let profile = Profile::from_csv_bytes(&std::fs::read(file).unwrap()).unwrap();
    let road = MeasuredSource::new(
        "concrete-slab-5m.csv",
        profile,
        20.0,
        ProfileTracks::Correlated,
    )
    .unwrap();
    StudySpec::new(Car::datum(), StudyRoad::Measured(road))
}

fn front_ask(adaptive: Option<AdaptiveOptions>) -> FrontAsk {
    FrontAsk {
        evaluator: EvaluatorSpec::Model(ModelKind::Quarter),
        plan: PlanSpec::AudzeEglais(10),
        method: Method::Stm(StmParams {
            grid: 11,
            levels: 1,
        }),
        pick: PickRule::MinMax,
        adaptive,
    }
}

/// Without cases, case 0 is the car itself: its map (built through the case set, the
/// loaded car and the case's road) is the plain map to rounding.
#[test]
fn case_zero_without_cases_is_the_plain_map() {
    let study = StudySpec::new(Car::datum(), StudyRoad::Iso(Road::default()));
    for model in [ModelKind::Quarter, ModelKind::Full] {
        let plain = study.map(&ask(model, None)).unwrap();
        let case = study.map(&ask(model, Some(0))).unwrap();
        assert!(matches!(case, StudyMap::Case(_)));
        let (plain, case) = (plain.into_map(), case.into_map());
        for (a, b) in [
            (&plain.bacc, &case.bacc),
            (&plain.dtl, &case.dtl),
            (&plain.sws, &case.sws),
        ] {
            assert_eq!(a.len(), 16);
            for (x, y) in a.iter().zip(b) {
                assert!((x / y - 1.0).abs() < 1e-12, "{model:?}: {x} vs {y}");
            }
        }
    }
    let e = study.map(&ask(ModelKind::Quarter, Some(1))).unwrap_err();
    assert!(e.to_string().starts_with("case: 1 is not a case"), "{e}");
}

/// On a measured road the map's fields are the road's models at each grid point, the
/// report names the road, and the front carries what reports say of it (an ISO
/// class's front does not).
#[test]
fn a_measured_road_runs_the_map_and_the_front_there() {
    let study = slab();
    let StudyRoad::Measured(m) = &study.road else {
        unreachable!()
    };
    let map = study
        .map(&ask(ModelKind::Quarter, None))
        .unwrap()
        .into_map();
    let model = MeasuredModel::new(ModelKind::Quarter, &study.car, m.shaped.clone());
    let g = grid(4);
    let (ks, cs) = (g.ks.values(), g.cs.values());
    // Map order: Cs rows, Ks columns.
    for (j, &c) in cs.iter().enumerate() {
        for (i, &k) in ks.iter().enumerate() {
            let e = model.evaluate(k, c).unwrap();
            let at = j * ks.len() + i;
            assert!((map.bacc[at] / e.bacc - 1.0).abs() < 1e-12);
            assert!((map.dtl[at] / e.dtl - 1.0).abs() < 1e-12);
            assert!((map.sws[at] / e.sws - 1.0).abs() < 1e-12);
        }
    }
    assert!(
        matches!(&map.road, crate::road::RoadScenario::Measured(r) if r.file == "concrete-slab-5m.csv")
    );
    let front = study.front(&front_ask(None)).unwrap();
    assert_eq!(
        front.road.as_ref().map(|r| r.file.as_str()),
        Some("concrete-slab-5m.csv")
    );
    let FrontReport::One(r) = &front.front else {
        panic!("one scenario's front")
    };
    // The datum is the full car on the road.
    let full = MeasuredModel::new(ModelKind::Full, &study.car, m.shaped.clone());
    let d = full
        .evaluate(study.car.front.spring, study.car.front.damper)
        .unwrap();
    assert!((r.datum.bacc / d.bacc - 1.0).abs() < 1e-12);
    let iso = StudySpec::new(Car::datum(), StudyRoad::Iso(Road::default()));
    assert!(iso.front(&front_ask(None)).unwrap().road.is_none());
}

/// What a study cannot combine is refused, naming the field.
#[test]
fn what_a_study_cannot_combine_is_refused_by_name() {
    let road = Road::default();
    let cases = CaseSet::new(&Car::datum(), &road, &[], &[], Combine::Worst).unwrap();
    let field = |e: RideError| match e {
        RideError::Field { field, .. } => field,
        other => panic!("{other}"),
    };
    let measured = slab();
    let with_cases = StudySpec {
        cases: Some(cases.clone()),
        ..slab()
    };
    let gpu = StudySpec {
        compute: Some(Compute::Gpu),
        ..slab()
    };
    assert_eq!(
        field(measured.map(&ask(ModelKind::Full, Some(0))).unwrap_err()),
        "road"
    );
    assert_eq!(
        field(with_cases.map(&ask(ModelKind::Full, None)).unwrap_err()),
        "road"
    );
    assert_eq!(
        field(with_cases.front(&front_ask(None)).unwrap_err()),
        "road"
    );
    assert_eq!(
        field(gpu.map(&ask(ModelKind::Full, None)).unwrap_err()),
        "compute"
    );
    let robust = StudySpec {
        cases: Some(cases),
        ..StudySpec::new(Car::datum(), StudyRoad::Iso(road))
    };
    let looped = front_ask(Some(AdaptiveOptions::default()));
    assert_eq!(field(robust.front(&looped).unwrap_err()), "adaptive");
    // A fit, the fidelity study and the report are of one scenario.
    let gp = SurrogateSpec::parse("gp-mul").unwrap();
    let e = robust.surrogate(gp, PlanSpec::AudzeEglais(5), None, None);
    assert_eq!(field(e.unwrap_err()), "cases");
    assert_eq!(field(robust.fidelity().unwrap_err()), "cases");
    let options = crate::study::adaptive::StudyOptions::default();
    assert_eq!(
        field(robust.adaptive_study(gp, &options).unwrap_err()),
        "cases"
    );
    assert_eq!(field(robust.report(None, 1, |_| {}).unwrap_err()), "cases");
    let robust_gpu = StudySpec {
        compute: Some(Compute::Gpu),
        ..robust
    };
    assert_eq!(
        field(robust_gpu.map(&ask(ModelKind::Full, None)).unwrap_err()),
        "compute"
    );
    assert_eq!(
        field(robust_gpu.front(&front_ask(None)).unwrap_err()),
        "compute"
    );
}
