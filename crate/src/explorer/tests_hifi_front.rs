//! The page's HiFi front against `ridelab optimize` on the HiFi, and its judgement of the
//! plane's front against the adaptive study's independent yardstick (`front_check`).

use super::*;
use crate::analysis::ModelKind;
use crate::evaluate::Evaluator;
use crate::gpu::ComputePath;
use crate::maps::Grid;
use crate::optimize::{Method, StmParams};
use crate::study::adaptive::{front_check, Decision, HifiFront};
use crate::study::{EvaluatorSpec, OptimizeRequest};
use crate::surrogate::PlanSpec;

const PAGE_STM: StmParams = StmParams {
    grid: studies::STM_GRID,
    levels: studies::STM_LEVELS,
};

/// The page's HiFi front is `ridelab optimize --evaluator full --grid 61 --levels 2`'s
/// bit for bit (designs, criteria, hypervolume, pick), on the datum scenario and on a
/// class C road at 30 m/s with independent tracks and a 16 mm limit; its HiFi run count is STM's
/// evaluations plus the datum's.
#[test]
fn hifi_front_is_optimize_on_the_full_car() {
    for patch in [(|_: &mut State| {}) as fn(&mut State), |s: &mut State| {
        s.class = "C".into();
        s.speed = 30.0;
        s.tracks = "independent".into();
        s.sws_limit = Some(0.016);
    }] {
        let mut st = State::default();
        patch(&mut st);
        let mut x = Session::new(st).unwrap();
        let view = x.hifi_front(None).unwrap();
        let s = x.scenario().clone();
        let cli = OptimizeRequest {
            evaluator: EvaluatorSpec::Model(ModelKind::Full),
            plan: PlanSpec::AudzeEglais(10),
            ..OptimizeRequest::new(
                &s.datum,
                &s.road,
                s.dbox,
                Method::Stm(PAGE_STM),
                s.objectives.clone(),
            )
        }
        .run_cpu()
        .unwrap();
        let f = &view.front.study;
        assert_eq!(f.front.len(), cli.study.front.len());
        for (a, b) in f.front.iter().zip(&cli.study.front) {
            assert_eq!(
                [a.ks, a.cs, a.bacc, a.dtl, a.sws],
                [b.ks, b.cs, b.bacc, b.dtl, b.sws]
            );
        }
        assert_eq!(f.hypervolume, cli.study.hypervolume);
        assert_eq!(
            (f.pick.ks, f.pick.cs),
            (cli.study.pick.ks, cli.study.pick.cs)
        );
        assert_eq!(view.hifi_runs, f.evaluations + 1);
        assert_eq!(view.compute, ComputePath::Cpu);
        // Its re-check is the HiFi itself.
        assert!(view
            .front
            .recheck
            .error_percent
            .iter()
            .all(|e| e.abs() < 1e-12));
    }
}

/// The plane's front judged on the HiFi equals the adaptive study's `front_check` of the
/// same surrogate against `HifiFront` with the page's STM (an independent path: its own
/// front, HiFi re-evaluation, feasibility and reference point) to 1e-12, and the
/// predicted hypervolume and pick gap follow from their definitions.
#[test]
fn plane_check_equals_the_adaptive_studys_yardstick() {
    let mut x = Session::new(State::default()).unwrap();
    let view = x.hifi_front(None).unwrap();
    let s = x.scenario().clone();
    let hifi = s.hifi().unwrap();
    let decision = Decision {
        objectives: s.objectives.clone(),
        ctx: crate::dos::DosContext::of_model(&s.datum, &hifi).unwrap(),
        stm: PAGE_STM,
    };
    let reference = HifiFront::new(&hifi, &decision, &s.dbox).unwrap();
    assert_eq!(reference.hypervolume, view.front.study.hypervolume);
    assert_eq!(reference.reference_point, view.front.study.reference_point);
    let fit = x.surrogate().unwrap();
    let check = front_check(&fit.model, &hifi, &decision, &s.dbox, &reference, 10).unwrap();
    let p = &view.plane;
    assert_eq!(p.model, "surrogate");
    assert_eq!(p.hifi_runs, fit.samples.len() + 1);
    assert_eq!(p.front_points, check.front_points);
    assert_eq!(p.hifi_feasible_points, check.hifi_feasible_points);
    assert!((p.hypervolume_ratio / check.hypervolume_ratio - 1.0).abs() < 1e-12);
    // The surrogate's front is good: its HiFi hypervolume is within 2 % of the HiFi's.
    assert!(
        (p.hypervolume_ratio - 1.0).abs() < 0.02,
        "{}",
        p.hypervolume_ratio
    );
    let plane = x.front("stm", Model::Surrogate).unwrap();
    let pts: Vec<[f64; 2]> = plane.study.front.iter().map(|q| [q.bacc, q.dtl]).collect();
    let hv = crate::optimize::hypervolume(&pts, view.front.study.reference_point);
    assert_eq!(p.hypervolume, hv);
    let (a, b) = (plane.recheck.rechecked, view.front.study.pick.criteria);
    assert!((p.pick_gap_percent[0] - 100.0 * (a.bacc / b.bacc - 1.0)).abs() < 1e-12);
    assert!((p.pick_gap_percent[1] - 100.0 * (a.dtl / b.dtl - 1.0)).abs() < 1e-12);
}

/// STM's starting grid handed in (as the GPU path does) gives the CPU front (to 1e-12:
/// STM's own grid coordinates may differ from the grid's by an ulp) when the values are
/// the CPU HiFi's, and says "gpu"; bad values are refused naming the
/// field, Wk comfort with GPU values naming `comfort`, and the session stays usable.
#[test]
fn handed_in_grid_values_make_the_same_front() {
    let mut x = Session::new(State::default()).unwrap();
    let cpu = x.hifi_front(None).unwrap();
    let s = x.scenario().clone();
    let n = studies::STM_GRID;
    let grid = Grid::over_box(&s.dbox, n, n).unwrap();
    let hifi = s.hifi().unwrap();
    let m = grid.len();
    let mut planes = vec![0.0; 3 * m];
    for j in 0..n {
        for i in 0..n {
            let (ks, cs) = grid.point(i, j);
            let c = hifi.evaluate(ks, cs).unwrap();
            let k = grid.index(i, j);
            (planes[k], planes[m + k], planes[2 * m + k]) = (c.bacc, c.dtl, c.sws);
        }
    }
    let gpu = x.hifi_front(Some(&planes)).unwrap();
    assert_eq!(gpu.compute, ComputePath::Gpu);
    let rel = |a: f64, b: f64| (a / b - 1.0).abs();
    assert!(rel(gpu.front.study.hypervolume, cpu.front.study.hypervolume) < 1e-12);
    assert_eq!(gpu.front.study.front.len(), cpu.front.study.front.len());
    for (a, b) in gpu.front.study.front.iter().zip(&cpu.front.study.front) {
        assert!(rel(a.ks, b.ks) < 1e-12 && rel(a.cs, b.cs) < 1e-12);
        assert!(rel(a.bacc, b.bacc) < 1e-12 && rel(a.dtl, b.dtl) < 1e-12);
    }
    assert_eq!(gpu.hifi_runs, cpu.hifi_runs);
    let field = |r: crate::error::Result<HifiFrontView>| match r {
        Err(crate::error::RideError::Field { field, .. }) => field,
        other => panic!("expected a field error, got {other:?}"),
    };
    assert_eq!(field(x.hifi_front(Some(&planes[1..]))), "values");
    let mut bad = planes.clone();
    bad[7] = f64::NAN;
    assert_eq!(field(x.hifi_front(Some(&bad))), "values");
    let mut st = x.state().clone();
    st.comfort = Some("wk".into());
    x.set_state(st).unwrap();
    assert_eq!(field(x.hifi_front(Some(&planes))), "comfort");
    // With Wk comfort the CPU HiFi front is the Wk one, judged against the LoFi's plane.
    let wk = x.hifi_front(None).unwrap();
    assert_eq!(wk.plane.model, "lofi");
    assert_eq!(wk.plane.hifi_runs, 1);
    assert!(wk.front.study.pick.criteria.bacc < cpu.front.study.pick.criteria.bacc);
}
