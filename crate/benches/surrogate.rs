//! Timings of the surrogates: fitting VBA-QTS to 10 HiFi samples (the HiFi runs included),
//! one prediction of all three criteria against one LoFi evaluation, and the whole fidelity
//! study (every approach x scheme x plan, validated on the 20 x 20 HiFi grid).
//!
//! Run: `cargo bench -p ridelab --bench surrogate`.

use criterion::{criterion_group, criterion_main, Criterion};
use ridelab::doe::audze_eglais;
use ridelab::study::study;
use ridelab::surrogate::{sample_plan, LmOptions, Setting, SurrogateSpec};
use ridelab::{Car, DesignBox, Evaluator, HiFi, LoFi, Road};
use std::hint::black_box;

fn surrogates(c: &mut Criterion) {
    let (car, road, design_box) = (Car::datum(), Road::default(), DesignBox::default());
    let setting = Setting::new(&car, &road, &design_box).unwrap();
    let hifi = HiFi::new(&car, &road).unwrap();
    let plan = audze_eglais(10, 1).unwrap();
    let spec = SurrogateSpec::parse("vba-qts").unwrap();
    let options = LmOptions::default();
    c.bench_function("vba-qts fit, 10 HiFi samples included", |b| {
        b.iter(|| {
            let samples = sample_plan(&hifi, black_box(&plan), &design_box).unwrap();
            spec.fit(&setting, &samples, &options).unwrap()
        })
    });

    let samples = sample_plan(&hifi, &plan, &design_box).unwrap();
    let model = spec.fit(&setting, &samples, &options).unwrap();
    c.bench_function("vba-qts predict (3 criteria, one point)", |b| {
        b.iter(|| {
            model
                .evaluate(black_box(23_000.0), black_box(1_700.0))
                .unwrap()
        })
    });
    let lofi = LoFi {
        car: car.clone(),
        road,
    };
    c.bench_function("LoFi evaluate (one point)", |b| {
        b.iter(|| {
            lofi.evaluate(black_box(23_000.0), black_box(1_700.0))
                .unwrap()
        })
    });

    let mut slow = c.benchmark_group("study");
    slow.sample_size(10);
    slow.bench_function("fidelity study (all approaches x schemes x plans)", |b| {
        b.iter(|| study(black_box(&car), &road, &design_box).unwrap())
    });
    slow.finish();
}

criterion_group!(benches, surrogates);
criterion_main!(benches);
