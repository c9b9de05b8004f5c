//! Criteria at one design point: LoFi (closed form) and HiFi by the residue route (the
//! route the maps use) against the modal route (the reference evaluator) in the same
//! run, with the Kronecker and frequency routes as baselines; and a 160 x 120 HiFi map
//! over the default design box by both routes, on one thread (the page's worker) and
//! on the native threads.

use criterion::{criterion_group, criterion_main, Criterion};
use ridelab::criteria::{criteria_exact, criteria_spectral};
use ridelab::design::DesignBox;
use ridelab::maps::{default_threads, Dcs, Grid, Scale};
use ridelab::model::full_car;
use ridelab::road::{Road, Tracks};
use ridelab::{Car, Evaluator, HiFi, LoFi};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let car = Car::datum();
    let road = Road::default();
    let lofi = LoFi {
        car: car.clone(),
        road,
    };
    let indep = Road {
        tracks: Tracks::Independent,
        ..road
    };
    let hifi = HiFi::new(&car, &road).unwrap();
    let hifi_indep = HiFi::new(&car, &indep).unwrap();
    let modal = HiFi::with_modal_route(&car, &road).unwrap();
    let modal_indep = HiFi::with_modal_route(&car, &indep).unwrap();
    let mut g = c.benchmark_group("criteria");
    g.bench_function("lofi_closed_form", |b| {
        b.iter(|| lofi.evaluate(black_box(21_000.0), black_box(1_400.0)))
    });
    g.bench_function("hifi_residue_correlated", |b| {
        b.iter(|| hifi.evaluate(black_box(21_000.0), black_box(1_400.0)))
    });
    g.bench_function("hifi_modal_correlated", |b| {
        b.iter(|| modal.evaluate(black_box(21_000.0), black_box(1_400.0)))
    });
    g.bench_function("hifi_residue_independent", |b| {
        b.iter(|| hifi_indep.evaluate(black_box(21_000.0), black_box(1_400.0)))
    });
    g.bench_function("hifi_modal_independent", |b| {
        b.iter(|| modal_indep.evaluate(black_box(21_000.0), black_box(1_400.0)))
    });
    g.bench_function("hifi_new_residue_correlated", |b| {
        b.iter(|| HiFi::new(black_box(&car), &road))
    });
    let full = full_car(&car);
    g.bench_function("hifi_kronecker_baseline", |b| {
        b.iter(|| criteria_exact(black_box(&full), &road))
    });
    g.bench_function("hifi_frequency_1e-6_baseline", |b| {
        b.iter(|| criteria_spectral(black_box(&full), &road, 1e-6))
    });
    g.finish();
    let grid = Grid::over_box(&DesignBox::default(), 160, 120).unwrap();
    let datum = (car.front.spring, car.front.damper);
    let mut m = c.benchmark_group("hifi_map_160x120");
    m.sample_size(10);
    for (name, threads) in [("1_thread", 1), ("threads", default_threads())] {
        for (route, e) in [("residue", &hifi), ("modal", &modal)] {
            m.bench_function(format!("{route}_{name}"), |b| {
                b.iter(|| Dcs::compute_with_threads(e, &grid, datum, Scale::Absolute, threads))
            });
        }
    }
    m.finish();
    // Every point above went by the route its name says.
    assert_eq!(hifi.route_counts().others(), 0);
    assert_eq!(hifi_indep.route_counts().others(), 0);
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(30).measurement_time(std::time::Duration::from_secs(3));
    targets = bench
}
criterion_main!(benches);
