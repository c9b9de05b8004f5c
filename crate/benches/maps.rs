//! Timings of the design maps: a LoFi 101 x 101 map and a HiFi 41 x 41 map of all three
//! criteria over the default design box (datum car, class B, 20 m/s), on all available
//! threads and on one; plus marching squares on the LoFi map; and both maps with the
//! ISO 2631-1 Wk-weighted comfort in the BAcc field (`--comfort wk`, issue #16).
//!
//! Run: `cargo bench -p ridelab --bench maps`.

use criterion::{criterion_group, criterion_main, Criterion};
use ridelab::comfort::WkComfort;
use ridelab::design::DesignBox;
use ridelab::maps::{auto_levels, contours, default_threads, Dcs, Grid, Scale};
use ridelab::{Car, HiFi, LoFi, Road};
use std::hint::black_box;

fn maps(c: &mut Criterion) {
    let car = Car::datum();
    let road = Road::default();
    let datum = (car.front.spring, car.front.damper);
    let threads = default_threads();
    let lofi = LoFi {
        car: car.clone(),
        road,
    };
    let hifi = HiFi::new(&car, &road).unwrap();
    let box_ = DesignBox::default();
    let g101 = Grid::over_box(&box_, 101, 101).unwrap();
    let g41 = Grid::over_box(&box_, 41, 41).unwrap();

    c.bench_function(&format!("lofi 101x101 ({threads} threads)"), |b| {
        b.iter(|| Dcs::compute(black_box(&lofi), &g101, datum, Scale::Absolute).unwrap())
    });
    c.bench_function("lofi 101x101 (1 thread)", |b| {
        b.iter(|| {
            Dcs::compute_with_threads(black_box(&lofi), &g101, datum, Scale::Absolute, 1).unwrap()
        })
    });
    let map = Dcs::compute(&lofi, &g101, datum, Scale::Absolute).unwrap();
    c.bench_function("contours 101x101, 10 levels x 3 criteria", |b| {
        b.iter(|| {
            for k in 0..3 {
                let f = map.field(k);
                black_box(contours(&g101, f, &auto_levels(f, 10)).unwrap());
            }
        })
    });

    let mut slow = c.benchmark_group("hifi");
    slow.sample_size(10);
    slow.bench_function(format!("hifi 41x41 ({threads} threads)"), |b| {
        b.iter(|| Dcs::compute(black_box(&hifi), &g41, datum, Scale::Absolute).unwrap())
    });
    slow.bench_function("hifi 41x41 (1 thread)", |b| {
        b.iter(|| {
            Dcs::compute_with_threads(black_box(&hifi), &g41, datum, Scale::Absolute, 1).unwrap()
        })
    });
    let wk_hifi = WkComfort::full(hifi.clone());
    slow.bench_function(format!("hifi 41x41 wk comfort ({threads} threads)"), |b| {
        b.iter(|| Dcs::compute(black_box(&wk_hifi), &g41, datum, Scale::Absolute).unwrap())
    });
    slow.finish();
    let wk_lofi = WkComfort::quarter(&car, &road);
    c.bench_function(&format!("lofi 41x41 wk comfort ({threads} threads)"), |b| {
        b.iter(|| Dcs::compute(black_box(&wk_lofi), &g41, datum, Scale::Absolute).unwrap())
    });
}

criterion_group!(benches, maps);
criterion_main!(benches);
