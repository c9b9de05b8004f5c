//! Cells per second of the GPU route against the CPU HiFi on the same grids, same run:
//! the datum car, class B, 20 m/s, correlated and independent tracks, over the default
//! design box at 41 x 41 (the page's CPU HiFi maps) and 160 x 120 (its LoFi maps).
//! The GPU is whatever adapter wgpu picks (lavapipe on a machine without one); the CPU
//! HiFi runs on all available threads.
//!
//! Run: `cargo bench -p ridelab --bench gpu` (criterion prints elements/s = cells/s).

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use ridelab::design::DesignBox;
use ridelab::gpu::{GpuMapper, MapInput};
use ridelab::maps::{default_threads, evaluate_grid, Grid};
use ridelab::{Car, HiFi, Road, Tracks};
use std::hint::black_box;

fn gpu(c: &mut Criterion) {
    let car = Car::datum();
    let threads = default_threads();
    let mapper = match GpuMapper::new() {
        Ok(Some(m)) => Some(m),
        Ok(None) => {
            eprintln!("no GPU adapter: only the CPU HiFi is timed");
            None
        }
        Err(e) => {
            eprintln!("GPU unusable ({e}): only the CPU HiFi is timed");
            None
        }
    };
    if let Some(m) = &mapper {
        eprintln!("GPU adapter: {} ({})", m.adapter_name(), m.backend());
    }
    for tracks in [Tracks::Correlated, Tracks::Independent] {
        let road = Road {
            tracks,
            ..Road::default()
        };
        let hifi = HiFi::new(&car, &road).unwrap();
        for (nx, ny) in [(41, 41), (160, 120)] {
            let grid = Grid::cells(&DesignBox::default(), nx, ny).unwrap();
            let mut g = c.benchmark_group(format!("{tracks:?} {nx}x{ny}").to_lowercase());
            g.sample_size(10);
            g.throughput(Throughput::Elements(grid.len() as u64));
            g.bench_function(format!("cpu hifi ({threads} threads)"), |b| {
                b.iter(|| evaluate_grid(black_box(&hifi), &grid, threads).unwrap())
            });
            if let Some(m) = &mapper {
                let input = MapInput::new(&car, &road, &grid).unwrap();
                g.bench_function(format!("gpu ({} nodes)", input.rule.len()), |b| {
                    b.iter(|| m.map(black_box(&input)).unwrap())
                });
                g.bench_function("gpu with the rule's set-up", |b| {
                    b.iter(|| m.map(&MapInput::new(&car, &road, &grid).unwrap()).unwrap())
                });
            }
            g.finish();
        }
    }
}

criterion_group!(benches, gpu);
criterion_main!(benches);
