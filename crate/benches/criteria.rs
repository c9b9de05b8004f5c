//! Criteria at one design point: LoFi (closed form) and HiFi (modal exact route, the
//! route the maps use), with the Kronecker and frequency routes as baselines measured
//! in the same run.

use criterion::{criterion_group, criterion_main, Criterion};
use ridelab::criteria::{criteria_exact, criteria_spectral};
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
    let hifi = HiFi::new(&car, &road).unwrap();
    let indep = Road {
        tracks: Tracks::Independent,
        ..road
    };
    let hifi_indep = HiFi::new(&car, &indep).unwrap();
    let mut g = c.benchmark_group("criteria");
    g.bench_function("lofi_closed_form", |b| {
        b.iter(|| lofi.evaluate(black_box(21_000.0), black_box(1_400.0)))
    });
    g.bench_function("hifi_modal_correlated", |b| {
        b.iter(|| hifi.evaluate(black_box(21_000.0), black_box(1_400.0)))
    });
    g.bench_function("hifi_modal_independent", |b| {
        b.iter(|| hifi_indep.evaluate(black_box(21_000.0), black_box(1_400.0)))
    });
    let full = full_car(&car);
    g.bench_function("hifi_kronecker_baseline", |b| {
        b.iter(|| criteria_exact(black_box(&full), &road))
    });
    g.bench_function("hifi_frequency_1e-6_baseline", |b| {
        b.iter(|| criteria_spectral(black_box(&full), &road, 1e-6))
    });
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(30).measurement_time(std::time::Duration::from_secs(3));
    targets = bench
}
criterion_main!(benches);
