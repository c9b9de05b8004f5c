//! Front-finding cost on a closed-form quarter car (a stand-in for a surrogate):
//! NSGA-II with 100 x 100 generations, STM on a 201 x 201 grid with 3 refinement levels.
//! Run: `cargo bench -p ridelab --bench optimize`.

use criterion::{criterion_group, criterion_main, Criterion};
use ridelab::dos::{DesignObjectives, DosContext};
use ridelab::optimize::{nsga2, stm, Nsga2Params, StmParams, SuspensionProblem};
use ridelab::{Criteria, DesignBox, Evaluator, Result};
use std::hint::black_box;

/// Closed-form quarter car on white-noise road velocity, `W = 2 pi^2 Gd n0^2 v` with
/// `Gd = 64e-6 m^3`, `n0 = 0.1 1/m`, `v = 20 m/s`; `ms = 467.7 kg`, `mu = 40 kg`,
/// `kt = 175500 N/m`, `M = ms + mu`: `var(BAcc) = W (ks^2 M + cs^2 kt) / (2 cs ms^2)`,
/// `var(SWS) = W M / (2 cs)`,
/// `var(DTL) = W / (2 cs) [kt^2 mu + (M/ms)^2 (ks^2 M + cs^2 kt) - 2 ks kt mu M / ms]`.
struct QuarterCar;

impl Evaluator for QuarterCar {
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
        let (ms, mu, kt) = (467.7, 40.0, 175_500.0);
        let w = 2.0 * std::f64::consts::PI.powi(2) * 64e-6 * 0.1f64.powi(2) * 20.0;
        let m = ms + mu;
        let q = ks * ks * m + cs * cs * kt;
        let dtl =
            w / (2.0 * cs) * (kt * kt * mu + (m / ms).powi(2) * q - 2.0 * ks * kt * mu * m / ms);
        Ok(Criteria {
            bacc: (w * q / (2.0 * cs * ms * ms)).sqrt(),
            dtl: dtl.sqrt(),
            sws: (w * m / (2.0 * cs)).sqrt(),
        })
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
