//! Front-finding cost on a closed-form quarter car (a stand-in for a surrogate):
//! NSGA-II with 100 x 100 generations, STM on a 201 x 201 grid with 3 refinement levels.
//! Run: `cargo bench -p ridelab --bench optimize`.

use criterion::{criterion_group, criterion_main, Criterion};
use ridelab::criteria::quarter_car_rms;
use ridelab::dos::{DesignObjectives, DosContext};
use ridelab::optimize::{nsga2, stm, Nsga2Params, StmParams, SuspensionProblem};
use ridelab::road::Road;
use ridelab::{Criteria, DesignBox, Evaluator, Result};
use std::hint::black_box;

/// The closed-form quarter car of the core (`criteria::quarter_car_rms`) with
/// `ms = 467.7 kg`, `mu = 40 kg`, `kt = 175500 N/m` on class B at 20 m/s.
struct QuarterCar;

impl Evaluator for QuarterCar {
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
        let q = ridelab::QuarterCar {
            ms: 467.7,
            mu: 40.0,
            ks,
            cs,
            kt: 175_500.0,
            ct: 0.0,
        };
        Ok(quarter_car_rms(&q, Road::default().intensity()))
    }
    fn name(&self) -> String {
        "quarter-closed-form".into()
    }
}

fn problem() -> SuspensionProblem<QuarterCar> {
    let ctx = DosContext {
        sprung_mass: 467.7,
        tire_stiffness: 175_500.0,
        datum: QuarterCar.evaluate(20_000.0, 1_500.0).unwrap(),
        static_wheel_load: 4_500.0,
    };
    SuspensionProblem::new(
        QuarterCar,
        DesignBox::default(),
        DesignObjectives::default(),
        ctx,
    )
    .unwrap()
}

fn fronts(c: &mut Criterion) {
    let ga = Nsga2Params {
        population: 100,
        generations: 100,
        ..Default::default()
    };
    c.bench_function("nsga2 100x100 quarter closed form", |b| {
        b.iter(|| nsga2(&problem(), black_box(&ga)).unwrap())
    });
    let map = StmParams {
        grid: 201,
        levels: 3,
    };
    c.bench_function("stm 201x201 + 3 levels quarter closed form", |b| {
        b.iter(|| stm(&problem(), black_box(&map)).unwrap())
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(30);
    targets = fronts
}
criterion_main!(benches);
