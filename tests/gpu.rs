//! The GPU route against the CPU HiFi (the reference, [`HiFi`]: the exact modal route):
//! the map of every case below equals the CPU HiFi's within 1e-4 relative on every cell,
//! on whatever adapter wgpu finds (lavapipe, Mesa's CPU Vulkan driver, on a machine
//! without a GPU).
//!
//! Without an adapter each test prints `SKIPPED (no GPU adapter)` and passes: the route's
//! arithmetic is still checked on the CPU, in f64 and in f32, by the unit tests of
//! `ridelab::gpu`. Install lavapipe with `apt-get install mesa-vulkan-drivers`.

use ridelab::design::DesignBox;
use ridelab::gpu::{Compute, ComputePath, GpuMapper, HiFiGrid, MapInput};
use ridelab::maps::{default_threads, evaluate_grid, Grid};
use ridelab::road::{RoadClass, Tracks};
use ridelab::{Car, Criteria, HiFi, Road};
use std::time::Instant;

/// Largest relative difference allowed on any cell, -.
const TOL: f64 = 1e-4;

/// Writes a line to stderr past the test harness's capture (`eprintln!` is captured
/// and shown only for failing tests): a skip must show in a passing run.
fn say(line: &str) {
    use std::io::Write;
    let _ = writeln!(std::io::stderr(), "{line}");
}

/// The adapter, or `None` after printing why the test is skipped. A driver that is there
/// but fails is an error, not a skip.
fn mapper(test: &str) -> Option<GpuMapper> {
    match GpuMapper::new() {
        Ok(Some(m)) => {
            say(&format!(
                "{test}: GPU adapter {} ({})",
                m.adapter_name(),
                m.backend()
            ));
            Some(m)
        }
        Ok(None) => {
            say(&format!(
                "{test}: SKIPPED (no GPU adapter; on Debian: apt-get install mesa-vulkan-drivers)"
            ));
            None
        }
        Err(e) => panic!("{test}: the GPU adapter is there but unusable: {e}"),
    }
}

/// The datum car and the extremes the issue names: Cs at the box's low end, heavy
/// unsprung masses, tyre damping, unequal track widths (a road warp on independent
/// tracks), and the other presets; each with the tracks it is run on.
fn cases() -> Vec<(&'static str, Car, Tracks, DesignBox)> {
    let datum = Car::datum();
    let full = DesignBox::default();
    let low_cs = DesignBox {
        cs_max: 1000.0,
        ..full
    };
    let mut heavy = datum.clone();
    heavy.front.unsprung_mass *= 2.0;
    heavy.rear.unsprung_mass *= 2.0;
    let mut tyre_damping = datum.clone();
    tyre_damping.front.tire_damping = 500.0;
    tyre_damping.rear.tire_damping = 500.0;
    let mut warp = datum.clone();
    warp.track_rear = warp.track_front - 0.05;
    let preset = |n: &str| Car::preset(n).expect("preset");
    vec![
        ("datum", datum.clone(), Tracks::Correlated, full),
        ("datum, low Cs", datum.clone(), Tracks::Correlated, low_cs),
        (
            "datum, independent",
            datum.clone(),
            Tracks::Independent,
            full,
        ),
        ("heavy unsprung", heavy.clone(), Tracks::Correlated, full),
        (
            "heavy, low Cs, independent",
            heavy,
            Tracks::Independent,
            low_cs,
        ),
        ("tyre damping", tyre_damping, Tracks::Correlated, full),
        ("road warp", warp.clone(), Tracks::Independent, full),
        ("road warp, low Cs", warp, Tracks::Independent, low_cs),
        ("suv", preset("suv"), Tracks::Independent, full),
        (
            "compact, low Cs",
            preset("compact"),
            Tracks::Correlated,
            low_cs,
        ),
    ]
}

/// Largest `|a / b - 1|` over every criterion of every cell.
fn max_rel(a: &[Criteria], b: &[Criteria]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .flat_map(|(x, y)| {
            x.to_array()
                .into_iter()
                .zip(y.to_array())
                .map(|(p, q)| (p / q - 1.0).abs())
        })
        .fold(0.0, f64::max)
}

/// Every case at 5, 10, 20 and 40 m/s, the road classes A to H in turn, on a 7 x 7
/// grid over the case's box (corners included).
#[test]
fn the_gpu_map_equals_the_cpu_hifi_on_every_cell() {
    let Some(gpu) = mapper("gpu map vs CPU HiFi") else {
        return;
    };
    let mut worst: f64 = 0.0;
    let (mut t_gpu, mut t_cpu, mut cells) = (0.0, 0.0, 0);
    for (k, (name, car, tracks, dbox)) in cases().into_iter().enumerate() {
        for (s, speed) in [5.0, 10.0, 20.0, 40.0].into_iter().enumerate() {
            let road = Road {
                class: RoadClass::ALL[(4 * k + s) % 8],
                speed,
                tracks,
            };
            let grid = Grid::over_box(&dbox, 7, 7).unwrap();
            let t0 = Instant::now();
            let hifi = HiFi::new(&car, &road).unwrap();
            let cpu = evaluate_grid(&hifi, &grid, default_threads()).unwrap();
            let t1 = Instant::now();
            let input = MapInput::new(&car, &road, &grid).unwrap();
            let got = gpu.map(&input).unwrap();
            t_gpu += t1.elapsed().as_secs_f64();
            t_cpu += (t1 - t0).as_secs_f64();
            cells += grid.len();
            let e = max_rel(&got, &cpu);
            eprintln!(
                "{name:28} {:?} {speed:4} m/s: {} nodes, max rel {e:.2e}",
                road.class,
                input.rule.len()
            );
            assert!(e <= TOL, "{name} at {speed} m/s: {e:.3e} > {TOL:e}");
            worst = worst.max(e);
        }
    }
    say(&format!(
        "gpu map vs CPU HiFi: worst {worst:.2e}; {cells} cells: GPU {:.0} cells/s (set-up included), CPU HiFi {:.0} cells/s ({} threads)",
        cells as f64 / t_gpu,
        cells as f64 / t_cpu,
        default_threads()
    ));
}

/// `Compute::Gpu` maps on the GPU and says so; `Compute::Cpu` is the CPU HiFi itself; off
/// the grid both are the CPU HiFi.
#[test]
fn a_hifi_grid_says_which_path_drew_it() {
    let car = Car::datum();
    let road = Road::default();
    let grid = Grid::over_box(&DesignBox::default(), 6, 5).unwrap();
    let hifi = HiFi::new(&car, &road).unwrap();
    let cpu = HiFiGrid::compute(HiFi::new(&car, &road).unwrap(), &grid, Compute::Cpu, 1).unwrap();
    assert_eq!(cpu.path(), ComputePath::Cpu);
    assert_eq!(cpu.adapter(), None);
    assert_eq!(cpu.values(), evaluate_grid(&hifi, &grid, 1).unwrap());
    if mapper("compute gpu").is_none() {
        return;
    }
    let gpu = HiFiGrid::compute(HiFi::new(&car, &road).unwrap(), &grid, Compute::Gpu, 1).unwrap();
    assert_eq!(gpu.path(), ComputePath::Gpu);
    assert!(gpu.adapter().is_some_and(|a| !a.is_empty()));
    assert!(max_rel(gpu.values(), cpu.values()) <= TOL);
    use ridelab::Evaluator;
    let off = (12_345.0, 1_234.0);
    assert_eq!(
        gpu.evaluate(off.0, off.1).unwrap(),
        hifi.evaluate(off.0, off.1).unwrap()
    );
}
