//! Timings of a measured road profile's path: reading a 4 km profile at 5 cm (80 000
//! samples, two tracks) from CSV text, describing it (Welch PSD of both tracks, coherence,
//! ISO 8608 fit; the target is under 100 ms), shaping it at 20 m/s (Welch PSDs and the
//! filter fits), and the criteria on the shaped road by the exact routes (the modal route
//! and the augmented Lyapunov equations behind it; quarter car and full car; the quarter
//! car's closed form, the LoFi of measured-road maps and surrogates) and by the
//! frequency route on the raw PSD (full car, 1e-6), and a design point with the
//! Wk-weighted comfort; the baseline is the full car's modal
//! route on the ISO class C road (the ISO map's route where the residue route declines).
//!
//! Run: `cargo bench -p ridelab --bench road_profile`.

use criterion::{criterion_group, criterion_main, Criterion};
use ridelab::analysis::{HiFi, ModelKind};
use ridelab::comfort::Comfort;
use ridelab::criteria::criteria_modal;
use ridelab::evaluate::Evaluator;
use ridelab::model::{full_car, quarter_car};
use ridelab::road::{Road, RoadClass};
use ridelab::road_profile::{
    criteria_shaped, criteria_shaped_modal, criteria_shaped_spectral, describe, synthesize,
    Profile, ProfileTracks, ShapedRoad, Synthesis,
};
use ridelab::road_profile::{MeasuredModel, ShapedQuarter};
use ridelab::Car;
use std::hint::black_box;

fn road_profile(c: &mut Criterion) {
    let profile = synthesize(&Synthesis {
        length: 4000.0,
        spacing: 0.05,
        waviness: 2.5,
        coherence_n: Some(0.3),
        ..Synthesis::default()
    })
    .unwrap();
    assert_eq!(profile.len(), 80_001);
    let text = profile.to_csv(2, 6);
    let mut g = c.benchmark_group("road_profile");
    g.sample_size(20);
    g.bench_function("parse 80k samples, 2 tracks", |b| {
        b.iter(|| Profile::from_csv(black_box(&text)).unwrap())
    });
    g.bench_function("describe 80k samples, 2 tracks", |b| {
        b.iter(|| describe(black_box(&profile)).unwrap())
    });
    g.bench_function("shape at 20 m/s, measured tracks", |b| {
        b.iter(|| ShapedRoad::from_profile(black_box(&profile), 20.0, ProfileTracks::Measured))
    });
    let road = ShapedRoad::from_profile(&profile, 20.0, ProfileTracks::Measured).unwrap();
    let car = Car::datum();
    let quarter = quarter_car(&car.quarter());
    let full = full_car(&car);
    g.bench_function("modal route, quarter car", |b| {
        b.iter(|| criteria_shaped_modal(black_box(&quarter), &road).unwrap())
    });
    let shaped_quarter = ShapedQuarter::new(road.clone());
    g.bench_function("closed form, quarter car", |b| {
        b.iter(|| shaped_quarter.criteria(black_box(&car.quarter())).unwrap())
    });
    g.bench_function("modal route, full car", |b| {
        b.iter(|| criteria_shaped_modal(black_box(&full), &road).unwrap())
    });
    let class_c = Road {
        class: RoadClass::C,
        ..Road::default()
    };
    g.bench_function("ISO class C, modal route, full car (baseline)", |b| {
        b.iter(|| criteria_modal(black_box(&full), &class_c).unwrap())
    });
    // A design point as a map evaluates it: the full car's residue route with the road's
    // filters (MeasuredModel), against the ISO HiFi's residue route.
    let measured = MeasuredModel::new(ModelKind::Full, &car, road.clone());
    let hifi = HiFi::new(&car, &class_c).unwrap();
    g.bench_function("residue route with the filters, full car point", |b| {
        b.iter(|| measured.evaluate(black_box(25e3), 1500.0).unwrap())
    });
    let measured_wk = measured.clone().with_comfort(Comfort::Wk);
    g.bench_function("Wk comfort with the filters, full car point", |b| {
        b.iter(|| measured_wk.evaluate(black_box(25e3), 1500.0).unwrap())
    });
    g.bench_function(
        "ISO class C, residue route, full car point (baseline)",
        |b| b.iter(|| hifi.evaluate(black_box(25e3), 1500.0).unwrap()),
    );
    g.bench_function("Lyapunov route, quarter car", |b| {
        b.iter(|| criteria_shaped(black_box(&quarter), &road).unwrap())
    });
    g.bench_function("Lyapunov route, full car", |b| {
        b.iter(|| criteria_shaped(black_box(&full), &road).unwrap())
    });
    g.bench_function("frequency route 1e-6, full car", |b| {
        b.iter(|| criteria_shaped_spectral(black_box(&full), &road, 1e-6).unwrap())
    });
    g.finish();
}

criterion_group!(benches, road_profile);
criterion_main!(benches);
