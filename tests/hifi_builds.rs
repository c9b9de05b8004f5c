//! One HiFi per optimisation (issue #28): `ridelab optimize` runs
//! [`OptimizeRequest::run`], which prepares the full car once for the front, a
//! surrogate's samples, the datum, the pick's re-check and a non-default pick (it was
//! built up to four times). Its own test binary: the counter is process-wide, and no other
//! test runs beside this one.

use ridelab::analysis::hifi_builds;
use ridelab::optimize::{Method, PickRule, StmParams};
use ridelab::study::{EvaluatorSpec, OptimizeRequest};
use ridelab::surrogate::{PlanSpec, SurrogateSpec};
use ridelab::{Car, Comfort, DesignBox, ModelKind, Road};

/// HiFi builds of one run, and its report.
fn builds_of(req: &OptimizeRequest) -> (u64, ridelab::study::OptimizeReport) {
    let before = hifi_builds();
    let r = req.run().unwrap();
    (hifi_builds() - before, r)
}

#[test]
fn every_optimisation_builds_its_hifi_once() {
    let car = Car::datum();
    let road = Road::default();
    let stm = Method::Stm(StmParams {
        grid: 20,
        ..StmParams::default()
    });
    let base = OptimizeRequest::new(&car, &road, DesignBox::default(), stm, Default::default());

    // --evaluator full (the path auto: the CPU on this machine, or the GPU's grid).
    let (n, full) = builds_of(&base);
    assert_eq!(n, 1, "optimize --evaluator full");
    // The datum is the HiFi's own, and the model's front is the HiFi's: the pick's
    // re-check equals its front value.
    let c = &full.study.pick.criteria;
    let h = &full.hifi_recheck.rechecked;
    assert!((c.bacc - h.bacc).abs() <= 1e-9 * h.bacc, "{c:?} vs {h:?}");

    // With a knee pick and the Wk comfort measure (repicked and re-checked on the same HiFi).
    let (n, _) = builds_of(&OptimizeRequest {
        pick: PickRule::Knee,
        comfort: Comfort::Wk,
        ..base.clone()
    });
    assert_eq!(n, 1, "optimize --evaluator full --pick knee --comfort wk");

    // A surrogate: its plan's samples on the same HiFi as the datum and re-check.
    let spec: SurrogateSpec = "rba-mul-rbf-mq".parse().unwrap();
    let (n, _) = builds_of(&OptimizeRequest {
        evaluator: EvaluatorSpec::Surrogate(spec),
        plan: PlanSpec::AudzeEglais(10),
        ..base.clone()
    });
    assert_eq!(n, 1, "optimize --evaluator rba-mul-rbf-mq");

    // The quarter car: the HiFi is the reference only.
    let (n, _) = builds_of(&OptimizeRequest {
        evaluator: EvaluatorSpec::Model(ModelKind::Quarter),
        ..base
    });
    assert_eq!(n, 1, "optimize --evaluator quarter");
}
