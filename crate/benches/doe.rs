//! Timings of the Audze-Eglais plans: the tabulated optimum (N = 10), the annealing heuristic
//! (N = 20, default budget) and the exact branch and bound (N = 10).
//!
//! Run: `cargo bench -p ridelab --bench doe`.

use criterion::{criterion_group, criterion_main, Criterion};
use ridelab::doe::{audze_eglais, exhaustive};
use std::hint::black_box;

fn plans(c: &mut Criterion) {
    c.bench_function("audze_eglais N=10 (tabulated)", |b| {
        b.iter(|| audze_eglais(black_box(10), 1).unwrap())
    });
    c.bench_function("audze_eglais N=20 (annealing)", |b| {
        b.iter(|| audze_eglais(black_box(20), 1).unwrap())
    });
    let mut slow = c.benchmark_group("exact");
    slow.sample_size(10);
    slow.bench_function("exhaustive N=10 (branch and bound)", |b| {
        b.iter(|| exhaustive(black_box(10)).unwrap())
    });
    slow.finish();
}

criterion_group!(benches, plans);
criterion_main!(benches);
