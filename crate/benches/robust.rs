//! Timings of the robust map (issue #16): 2 load cases (driver only, fully laden) x 3
//! speeds (10, 20, 30 m/s on class B), worst case, against the single-case map in the
//! same run, on the LoFi (101 x 101) and the HiFi (41 x 41, CPU), all available threads.
//! The issue asks for the robust map at most 6x the single-case map.
//!
//! Run: `cargo bench -p ridelab --bench robust`.

use criterion::{criterion_group, criterion_main, Criterion};
use ridelab::analysis::ModelKind;
use ridelab::design::DesignBox;
use ridelab::maps::Grid;
use ridelab::robust::{CaseSet, Combine, LoadCase, Operating};
use ridelab::study::{MapRequest, MapSettings};
use ridelab::{Car, Road, RoadClass};
use std::hint::black_box;

fn robust(c: &mut Criterion) {
    let car = Car::datum();
    let road = Road::default();
    let loads = [
        LoadCase::base(),
        LoadCase {
            name: "fully laden".into(),
            mass: 350.0,
            x: -0.3,
            ..LoadCase::base()
        },
    ];
    let ops: Vec<Operating> = [10.0, 20.0, 30.0]
        .map(|speed| Operating {
            class: RoadClass::B,
            speed,
            weight: 1.0,
        })
        .to_vec();
    let set = CaseSet::new(&car, &road, &loads, &ops, Combine::Worst).unwrap();
    for (model, n, name) in [
        (ModelKind::Quarter, 101, "lofi"),
        (ModelKind::Full, 41, "hifi"),
    ] {
        let settings = MapSettings {
            grid: Grid::over_box(&DesignBox::default(), n, n).unwrap(),
            ..MapSettings::default()
        };
        interleaved(
            name,
            n,
            || {
                MapRequest::new(model, &car, &road, settings.clone())
                    .run()
                    .unwrap();
            },
            || {
                MapRequest::new(model, &car, &road, settings.clone())
                    .run_robust(&set)
                    .unwrap();
            },
        );
        let mut g = c.benchmark_group(format!("robust {name} {n}x{n}"));
        g.sample_size(10);
        g.bench_function("single case", |b| {
            b.iter(|| {
                MapRequest::new(model, black_box(&car), &road, settings.clone())
                    .run()
                    .unwrap()
            })
        });
        g.bench_function("2 load cases x 3 speeds", |b| {
            b.iter(|| {
                MapRequest::new(model, black_box(&car), &road, settings.clone())
                    .run_robust(&set)
                    .unwrap()
            })
        });
        g.finish();
    }
}

/// On a shared machine the load drifts between criterion's groups; this times the two
/// maps alternately (21 rounds) and prints the medians and the median of the per-round
/// ratios, so both sides see the same load.
fn interleaved(name: &str, n: usize, single: impl Fn(), robust: impl Fn()) {
    let time = |f: &dyn Fn()| {
        let t = std::time::Instant::now();
        f();
        t.elapsed().as_secs_f64()
    };
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let (mut a, mut b, mut r) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..21 {
        let (ta, tb) = (time(&single), time(&robust));
        a.push(ta);
        b.push(tb);
        r.push(tb / ta);
    }
    println!(
        "interleaved {name} {n}x{n}: single case median {:.2} ms, 2 load cases x 3 speeds median {:.2} ms, median per-round ratio {:.2}x",
        1e3 * median(a),
        1e3 * median(b),
        median(r)
    );
}

criterion_group!(benches, robust);
criterion_main!(benches);
