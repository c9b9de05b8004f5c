//! The HiFi evaluator's residue route against the exact routes, and its fallbacks.
//!
//! Reference on every cell: the reference evaluator [`HiFi::with_modal_route`] (the modal
//! route on the symmetric half or the full car, the Kronecker route where it declines),
//! itself checked here against the Kronecker route on the full 7-DOF car (196 x 196
//! Lyapunov operator) on the grid's diagonal and at the cell where the two differ most. Comparing every cell with the Kronecker
//! route directly would cost about 1.4 ms a cell (minutes in a debug build); the modal
//! route costs 30 to 100 us.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
mod common;

use ridelab::analysis::{HiFiRoute, Routed};
use ridelab::car::{Axle, Car, PRESETS};
use ridelab::criteria::{criteria_exact, criteria_spectral};
use ridelab::design::DesignBox;
use ridelab::maps::{Dcs, Grid, Scale};
use ridelab::model::full_car;
use ridelab::road::{Road, RoadClass, Tracks};
use ridelab::{Criteria, Evaluator, HiFi};

fn max_rel(a: Criteria, b: Criteria) -> f64 {
    a.to_array()
        .iter()
        .zip(b.to_array())
        .map(|(x, y)| (x / y - 1.0).abs())
        .fold(0.0, f64::max)
}

/// A physically plausible car (the ranges of `tests/models.rs`), equal track widths so
/// that independent tracks give no road warp; tyre damping when `damped`.
fn random_car(rng: &mut ChaCha8Rng, damped: bool) -> Car {
    let mut axle = |mu: (f64, f64)| Axle {
        unsprung_mass: rng.random_range(mu.0..mu.1),
        spring: rng.random_range(12_000.0..45_000.0),
        damper: rng.random_range(600.0..4_000.0),
        tire_stiffness: rng.random_range(150_000.0..300_000.0),
        tire_damping: if damped {
            rng.random_range(50.0..400.0)
        } else {
            0.0
        },
    };
    let front = axle((25.0, 60.0));
    let rear = axle((25.0, 60.0));
    let t = rng.random_range(1.35..1.7);
    Car {
        name: "random".into(),
        source: "test".into(),
        sprung_mass: rng.random_range(900.0..2200.0),
        pitch_inertia: rng.random_range(1200.0..4000.0),
        roll_inertia: rng.random_range(300.0..900.0),
        a: rng.random_range(0.9..1.6),
        b: rng.random_range(1.1..1.9),
        track_front: t,
        track_rear: t,
        front,
        rear,
    }
}

/// The cars of the matrix: the presets as shipped and with tyre damping, 20 seeded
/// random cars (every other one with tyre damping) and three extreme cars.
fn cars() -> Vec<Car> {
    let mut cars: Vec<Car> = Vec::new();
    for (name, _) in PRESETS {
        let car = Car::preset(name).unwrap();
        let mut damped = car.clone();
        damped.front.tire_damping = 150.0;
        damped.rear.tire_damping = 150.0;
        cars.push(car);
        cars.push(damped);
    }
    let mut rng = ChaCha8Rng::seed_from_u64(18);
    cars.extend((0..20).map(|i| random_car(&mut rng, i % 2 == 1)));
    cars.extend(extreme_cars());
    cars
}

/// Cars at the edges of what a user could load: a light, stiff racing car on stiff
/// tyres; a heavy van with heavy axles, soft tyres and strong tyre damping; and a car
/// with a tiny pitch and roll inertia and a far-forward centre of mass.
fn extreme_cars() -> Vec<Car> {
    let datum = Car::datum();
    let mut race = datum.clone();
    race.name = "extreme: racing".into();
    race.sprung_mass = 550.0;
    race.pitch_inertia = 450.0;
    race.roll_inertia = 120.0;
    for ax in [&mut race.front, &mut race.rear] {
        ax.unsprung_mass = 18.0;
        ax.spring = 120_000.0;
        ax.damper = 6_000.0;
        ax.tire_stiffness = 500_000.0;
    }
    let mut van = datum.clone();
    van.name = "extreme: van".into();
    van.sprung_mass = 3_200.0;
    van.pitch_inertia = 9_000.0;
    van.roll_inertia = 2_400.0;
    van.a = 1.9;
    van.b = 1.6;
    for ax in [&mut van.front, &mut van.rear] {
        ax.unsprung_mass = 120.0;
        ax.tire_stiffness = 110_000.0;
        ax.tire_damping = 2_000.0;
    }
    let mut nose = datum;
    nose.name = "extreme: nose-heavy, small inertias".into();
    nose.pitch_inertia = 150.0;
    nose.roll_inertia = 40.0;
    nose.a = 0.35;
    nose.b = 2.45;
    vec![race, van, nose]
}

#[test]
fn residue_route_matches_the_exact_routes_on_every_cell() {
    let cars = cars();
    let speeds = [
        3.0, 45.0, 20.0, 8.0, 33.0, 12.5, 27.0, 40.0, 5.5, 16.0, 38.0,
    ];
    let grid = Grid::over_box(&DesignBox::default(), 20, 20).unwrap();
    let (mut worst, mut worst_kron, mut worst_modal_kron) = (0.0f64, 0.0f64, 0.0f64);
    let (mut cells, mut fallbacks) = (0usize, 0u64);
    let mut case = 0;
    for car in &cars {
        for tracks in [Tracks::Correlated, Tracks::Independent] {
            let road = Road {
                class: RoadClass::ALL[case % 8],
                speed: speeds[case % speeds.len()],
                tracks,
            };
            case += 1;
            let hifi = HiFi::new(car, &road).unwrap();
            assert!(hifi.has_residue_route(), "{car:?} {road:?}");
            let reference = HiFi::with_modal_route(car, &road).unwrap();
            // The Kronecker route on the full car, for both routes; the bound must cover
            // the residue route's error (half of it for an RMS).
            let mut against_kronecker = |ks: f64, cs: f64, r: &Routed| {
                let full = full_car(&car.with_front(ks, cs).unwrap());
                let kron = criteria_exact(&full, &road).unwrap();
                let k = max_rel(r.criteria, kron);
                assert!(k <= 1e-8, "{} {road:?} ({ks}, {cs}): {k:e}", car.name);
                if let Some(b) = r.bound {
                    assert!(k <= 0.5 * b + 1e-13, "bound {b:e} error {k:e}");
                }
                worst_kron = worst_kron.max(k);
                let m = max_rel(reference.evaluate(ks, cs).unwrap(), kron);
                worst_modal_kron = worst_modal_kron.max(m);
            };
            // The cell where the two routes differ most, checked on the Kronecker route too.
            let mut widest: Option<(f64, f64, f64, Routed)> = None;
            for j in 0..grid.cs.n {
                for i in 0..grid.ks.n {
                    let (ks, cs) = grid.point(i, j);
                    let r = hifi.evaluate_routed(ks, cs).unwrap();
                    let e = max_rel(r.criteria, reference.evaluate(ks, cs).unwrap());
                    assert!(
                        e <= 1e-8,
                        "{} {road:?} ({ks}, {cs}) {:?}: {e:e}",
                        car.name,
                        r.route
                    );
                    worst = worst.max(e);
                    cells += 1;
                    if i == j {
                        against_kronecker(ks, cs, &r);
                    } else if widest.is_none_or(|w| e > w.0) {
                        widest = Some((e, ks, cs, r));
                    }
                }
            }
            if let Some((_, ks, cs, r)) = widest {
                against_kronecker(ks, cs, &r);
            }
            let counts = hifi.route_counts();
            assert_eq!(counts.residue + counts.others(), 400);
            fallbacks += counts.others();
        }
    }
    println!(
        "{cells} cells, {} cases: residue vs reference max {worst:.2e}; on the diagonals and \
         each case's widest cell, residue vs Kronecker max {worst_kron:.2e}, reference vs \
         Kronecker {worst_modal_kron:.2e}; {fallbacks} fallbacks",
        case
    );
    assert!(worst_modal_kron <= 1e-8, "{worst_modal_kron:e}");
    assert!(
        fallbacks * 100 <= cells as u64,
        "{fallbacks} of {cells} cells fell back"
    );
}

#[test]
fn a_wide_box_and_extreme_designs_stay_exact() {
    // Far outside the default box: very soft and very stiff springs, light and heavy
    // damping (overdamped body modes: real roots).
    let car = Car::datum();
    for tracks in [Tracks::Correlated, Tracks::Independent] {
        let road = Road {
            tracks,
            ..Road::default()
        };
        let hifi = HiFi::new(&car, &road).unwrap();
        let reference = HiFi::with_modal_route(&car, &road).unwrap();
        let grid = Grid::parse("2000:200000:12", "50:30000:12").unwrap();
        for j in 0..grid.cs.n {
            for i in 0..grid.ks.n {
                let (ks, cs) = grid.point(i, j);
                let r = hifi.evaluate_routed(ks, cs).unwrap();
                let exact =
                    criteria_exact(&full_car(&car.with_front(ks, cs).unwrap()), &road).unwrap();
                let e = max_rel(r.criteria, exact);
                assert!(e <= 1e-8, "({ks}, {cs}) {:?}: {e:e}", r.route);
                let m = max_rel(r.criteria, reference.evaluate(ks, cs).unwrap());
                assert!(m <= 1e-8, "({ks}, {cs}): {m:e}");
            }
        }
        println!("{tracks:?}: {:?}", hifi.route_counts());
        assert!(
            hifi.route_counts().residue >= 100,
            "{:?}",
            hifi.route_counts()
        );
    }
}

#[test]
fn repeated_roots_fall_back_to_an_exact_route_and_say_so() {
    let car = common::twin_axle_car();
    let (ks, cs) = (car.front.spring, car.front.damper);
    for tracks in [Tracks::Correlated, Tracks::Independent] {
        let road = Road {
            tracks,
            ..Road::default()
        };
        let hifi = HiFi::new(&car, &road).unwrap();
        let r = hifi.evaluate_routed(ks, cs).unwrap();
        assert_ne!(r.route, HiFiRoute::Residue, "{tracks:?}");
        assert_eq!(r.bound, None);
        assert_eq!(hifi.route_counts().others(), 1);
        assert_eq!(hifi.route_counts().residue, 0);
        let exact = criteria_exact(&full_car(&car), &road).unwrap();
        assert!(
            max_rel(r.criteria, exact) <= 1e-8,
            "{tracks:?} {:?}",
            r.route
        );
        // Away from the coincidence the residue route holds again.
        let near = hifi.evaluate_routed(1.3 * ks, cs).unwrap();
        assert_eq!(near.route, HiFiRoute::Residue);
        let exact =
            criteria_exact(&full_car(&car.with_front(1.3 * ks, cs).unwrap()), &road).unwrap();
        assert!(max_rel(near.criteria, exact) <= 1e-8);
        println!("{tracks:?}: {:?} then {:?}", r.route, hifi.route_counts());
    }
}

#[test]
fn road_warp_still_goes_to_the_frequency_route() {
    let mut car = Car::datum();
    car.track_front = 1.522;
    car.track_rear = 1.510;
    let road = Road {
        tracks: Tracks::Independent,
        ..Road::default()
    };
    let hifi = HiFi::new(&car, &road).unwrap();
    let r = hifi
        .evaluate_routed(car.front.spring, car.front.damper)
        .unwrap();
    assert_eq!(r.route, HiFiRoute::Spectral);
    let sp = criteria_spectral(&full_car(&car), &road, 1e-8).unwrap();
    assert_eq!(r.criteria, sp.criteria);
}

#[test]
fn a_map_goes_by_the_residue_route_and_equals_its_points() {
    let car = Car::datum();
    let road = Road::default();
    let hifi = HiFi::new(&car, &road).unwrap();
    let grid = Grid::parse("10000:40000:16", "500:4000:12").unwrap();
    let map = Dcs::compute(
        &hifi,
        &grid,
        (car.front.spring, car.front.damper),
        Scale::Absolute,
    )
    .unwrap();
    // 192 cells and the datum, all by the residue route, on whatever threads the map used.
    assert_eq!(hifi.route_counts().residue, 193);
    assert_eq!(hifi.route_counts().others(), 0);
    let reference = HiFi::with_modal_route(&car, &road).unwrap();
    for j in 0..grid.cs.n {
        for i in 0..grid.ks.n {
            let (ks, cs) = grid.point(i, j);
            assert_eq!(map.criteria_at(i, j), hifi.evaluate(ks, cs).unwrap());
            assert!(max_rel(map.criteria_at(i, j), reference.evaluate(ks, cs).unwrap()) <= 1e-8);
        }
    }
}

#[test]
fn bad_designs_are_refused_with_the_field() {
    let hifi = HiFi::new(&Car::datum(), &Road::default()).unwrap();
    for (ks, cs, field) in [
        (0.0, 1000.0, "ks"),
        (f64::NAN, 1000.0, "ks"),
        (20_000.0, 0.0, "cs"),
        (20_000.0, -5.0, "cs"),
        (20_000.0, f64::INFINITY, "cs"),
    ] {
        let e = hifi.evaluate(ks, cs).unwrap_err().to_string();
        assert!(e.starts_with(field), "{ks} {cs}: {e}");
    }
    assert_eq!(
        hifi.route_counts().residue + hifi.route_counts().others(),
        0
    );
}
