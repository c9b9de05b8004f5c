//! Pareto fronts on the HiFi model itself, against a brute-force 200 x 200 reference front.

use ridelab::design::DesignBox;
use ridelab::dos::{DesignObjectives, DosContext};
use ridelab::optimize::{
    hypervolume, min_max_pick, non_dominated, normalised_distances, run_study, FrontPoint, Method,
    Nsga2Params, StmParams, SuspensionProblem,
};
use ridelab::road::Road;
use ridelab::{Car, Evaluator, HiFi};

#[test]
fn stm_and_nsga2_reach_995_permille_of_the_brute_force_hifi_front() {
    let car = Car::datum();
    let road = Road::default();
    let hifi = HiFi::new(&car, &road).unwrap();
    let datum = hifi.evaluate(car.front.spring, car.front.damper).unwrap();
    let q = car.quarter();
    let ctx = DosContext {
        sprung_mass: q.ms,
        tire_stiffness: q.kt,
        datum,
        static_wheel_load: car.front_wheel_load(),
    };
    let objectives = DesignObjectives::default();
    let b = DesignBox::default();

    // Brute force: a 200 x 200 grid of HiFi evaluations, feasible non-dominated points.
    let n = 200;
    let mut pts = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let (ks, cs) = b.scale(i as f64 / (n - 1) as f64, j as f64 / (n - 1) as f64);
            let c = hifi.evaluate(ks, cs).unwrap();
            if objectives.violation(&ctx, ks, cs, &c) == 0.0 {
                pts.push([c.bacc, c.dtl]);
            }
        }
    }
    let reference_front: Vec<[f64; 2]> = non_dominated(&pts).into_iter().map(|i| pts[i]).collect();
    assert!(reference_front.len() > 20);
    let nadir = reference_front
        .iter()
        .fold([f64::MIN; 2], |a, p| [a[0].max(p[0]), a[1].max(p[1])]);
    let ideal = reference_front
        .iter()
        .fold([f64::MAX; 2], |a, p| [a[0].min(p[0]), a[1].min(p[1])]);
    let r = [
        nadir[0] + 0.1 * (nadir[0] - ideal[0]),
        nadir[1] + 0.1 * (nadir[1] - ideal[1]),
    ];
    let hv_ref = hypervolume(&reference_front, r);

    let problem = SuspensionProblem::new(hifi.clone(), b, objectives, ctx).unwrap();
    for method in [
        Method::Stm(StmParams {
            grid: 101,
            levels: 3,
        }),
        Method::Nsga2(Nsga2Params {
            population: 100,
            generations: 100,
            seed: 1,
            ..Nsga2Params::default()
        }),
    ] {
        let study = run_study(&problem, &method, Some(r)).unwrap();
        let ratio = study.hypervolume / hv_ref;
        assert!(
            ratio >= 0.995,
            "{method:?}: {ratio:.5} of the brute-force hypervolume"
        );
        // Every front point meets the SWS limit on the HiFi.
        assert!(study.front.iter().all(|p| p.sws <= 0.007 * (1.0 + 1e-9)));
        check_pick(&study.front, &datum);
    }
}

/// The pick is on the front, and moving along the front from it makes one normalised
/// objective worse than the pick's worst.
fn check_pick(front: &[FrontPoint], datum: &ridelab::Criteria) {
    let pick = min_max_pick(front, datum).unwrap();
    let f: Vec<[f64; 2]> = front.iter().map(|p| [p.bacc, p.dtl]).collect();
    let nd = non_dominated(&f);
    assert!(nd.contains(&pick.index), "pick is non-dominated");
    let d = normalised_distances(front, datum);
    let worst = d[pick.index][0].max(d[pick.index][1]);
    for k in [pick.index.wrapping_sub(1), pick.index + 1] {
        if let Some(dk) = d.get(k) {
            assert!(
                dk[0].max(dk[1]) >= worst - 1e-12,
                "neighbour {k} is no better"
            );
        }
    }
}
