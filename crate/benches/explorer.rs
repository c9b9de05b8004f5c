//! Timings of what the page does on an edit, natively (the page measures the same calls
//! in wasm with performance.now()): the surrogate's fit, a 160 x 120 map of it computed
//! afresh and with its values kept (an objective edit), and the STM front on it against
//! the same front on the LoFi (the baseline), and the HiFi's own front beside them. All
//! through the page's [`Session`].
//!
//! Run: `cargo bench -p ridelab --bench explorer`.

use criterion::{criterion_group, criterion_main, Criterion};
use ridelab::analysis::ModelKind;
use ridelab::explorer::{Model, Session, State};
use std::cell::Cell;
use std::hint::black_box;

/// A session on the default view at a speed of `20 + i / 1000` m/s: a new speed per
/// iteration defeats the session's kept fit and map values where a fresh computation is timed.
fn at_speed(i: u64) -> Session {
    Session::new(State {
        speed: 20.0 + i as f64 * 1e-3,
        ..State::default()
    })
    .unwrap()
}

fn explorer(c: &mut Criterion) {
    let n = Cell::new(0u64);
    let next = || {
        n.set(n.get() + 1);
        at_speed(n.get())
    };
    c.bench_function("fit rba-mul-rbf-mq on ae:10 (10 HiFi runs included)", |b| {
        b.iter(|| black_box(next().surrogate().unwrap()))
    });
    c.bench_function("surrogate map 160x120, fresh (fit included)", |b| {
        b.iter(|| black_box(next().map(Model::Surrogate, 160, 120).unwrap()))
    });
    let mut s = at_speed(0);
    let mut limit = 0.007;
    c.bench_function("surrogate map 160x120, values kept, new SWS limit", |b| {
        b.iter(|| {
            limit += 1e-7;
            s.set_state(State {
                sws_limit: Some(limit),
                ..s.state().clone()
            })
            .unwrap();
            black_box(s.map(Model::Surrogate, 160, 120).unwrap())
        })
    });
    c.bench_function("lofi map 160x120, fresh", |b| {
        b.iter(|| black_box(next().map(Model::LoFi, 160, 120).unwrap()))
    });
    c.bench_function(
        "front stm 61x61 + 2 levels on the surrogate (fit kept)",
        |b| b.iter(|| black_box(s.front("stm", Model::Surrogate).unwrap())),
    );
    c.bench_function("front stm 61x61 + 2 levels on the LoFi (baseline)", |b| {
        b.iter(|| black_box(s.front("stm", Model::LoFi).unwrap()))
    });
    // A slider step (issue #28): the session's one call, and the LoFi column's part of
    // it, the quarter car's full report (with its frequency-route check) against its
    // readout (without).
    let mut ks = 20_000.0;
    c.bench_function(
        "slider step: design_step (LoFi and HiFi readouts, surrogate)",
        |b| {
            b.iter(|| {
                ks += 1.0;
                s.set_design(ks, 1_500.0).unwrap();
                black_box(s.design_step(Model::Surrogate, true).unwrap())
            })
        },
    );
    c.bench_function(
        "lofi report at a design (frequency-route check included)",
        |b| b.iter(|| black_box(s.report(ModelKind::Quarter).unwrap())),
    );
    c.bench_function("lofi readout at a design (no check)", |b| {
        b.iter(|| black_box(s.readout(ModelKind::Quarter).unwrap()))
    });
    // The objective plane's HiFi front (issue #13): STM on the full car and the
    // surrogate's front judged on the HiFi against it (fit kept).
    c.bench_function(
        "hifi front stm 61x61 + 2 levels on the full car, plane front judged",
        |b| b.iter(|| black_box(s.hifi_front(None).unwrap())),
    );
}

criterion_group!(benches, explorer);
criterion_main!(benches);
