//! The HiFi of one car on several roads ([`HiFiRoads`], issue #16) against each road's
//! own [`HiFi`]: the same criteria, route and bound bit for bit, on the presets, a
//! loaded car, a car whose residue route must fall back, and a road warp; and the fact
//! the sharing rests on, that the ISO 8608 class only scales the criteria by
//! `sqrt(Gd / Gd')` at one speed.

mod common;

use ridelab::analysis::{HiFiRoads, HiFiRoute, Routed};
use ridelab::car::{Car, PRESETS};
use ridelab::design::DesignBox;
use ridelab::road::{Road, RoadClass, Tracks};
use ridelab::robust::LoadCase;
use ridelab::{Evaluator, HiFi};

/// Every class at every speed of 5 to 40 m/s (classes of one speed next to each other,
/// so they share the delay terms), on `tracks`.
fn roads(tracks: Tracks) -> Vec<Road> {
    let mut roads = Vec::new();
    for speed in [5.0, 12.5, 20.0, 31.0, 40.0] {
        for class in RoadClass::ALL {
            roads.push(Road {
                class,
                speed,
                tracks,
            });
        }
    }
    roads
}

/// The box corners, its centre, points inside, the car's own design and a weakly damped
/// one (outside the box).
fn designs(car: &Car) -> Vec<(f64, f64)> {
    let b = DesignBox::default();
    vec![
        (b.ks_min, b.cs_min),
        (b.ks_max, b.cs_min),
        (b.ks_min, b.cs_max),
        (b.ks_max, b.cs_max),
        (0.5 * (b.ks_min + b.ks_max), 0.5 * (b.cs_min + b.cs_max)),
        (13_750.0, 2_187.5),
        (33_000.0, 875.0),
        (car.front.spring, car.front.damper),
        (20_000.0, 60.0),
    ]
}

fn cars() -> Vec<Car> {
    let mut cars: Vec<Car> = PRESETS
        .iter()
        .map(|(name, _)| Car::preset(name).unwrap())
        .collect();
    let mut damped = Car::datum();
    damped.front.tire_damping = 150.0;
    damped.rear.tire_damping = 150.0;
    cars.push(damped);
    let laden = LoadCase {
        name: "fully laden".into(),
        mass: 350.0,
        x: -0.3,
        y: 0.4,
        z: 0.1,
        ..LoadCase::base()
    };
    cars.push(laden.apply(&Car::datum(), "load_cases[0]").unwrap());
    cars.push(common::twin_axle_car());
    cars
}

/// Every road's [`HiFiRoads::evaluate_routed`] equals its own HiFi's, bit for bit (the
/// criteria, the route and the bound), and so do the route counts.
fn assert_same(car: &Car, roads: &[Road], shared: bool) -> (u64, u64) {
    let many = HiFiRoads::new(car, roads).unwrap();
    assert_eq!(many.is_shared(), shared, "{}", car.name);
    let own: Vec<HiFi> = roads.iter().map(|r| HiFi::new(car, r).unwrap()).collect();
    for (ks, cs) in designs(car) {
        let got = many.evaluate_routed(ks, cs);
        assert_eq!(got.len(), roads.len());
        for (k, (g, h)) in got.into_iter().zip(&own).enumerate() {
            let want: Routed = h.evaluate_routed(ks, cs).unwrap();
            let g = g.unwrap();
            assert_eq!(
                g, want,
                "{} on {:?} at ({ks}, {cs}), road {k}",
                car.name, roads[k]
            );
            // Bit for bit, not only ==.
            for (a, b) in g.criteria.to_array().iter().zip(want.criteria.to_array()) {
                assert_eq!(a.to_bits(), b.to_bits());
            }
        }
        let values = many.evaluate(ks, cs).unwrap();
        for (v, h) in values.iter().zip(&own) {
            assert_eq!(*v, h.evaluate(ks, cs).unwrap());
        }
    }
    let (mut residue, mut others) = (0, 0);
    for (h, o) in many.hifis().iter().zip(&own) {
        let (a, b) = (h.route_counts(), o.route_counts());
        assert_eq!(a, b);
        residue += a.residue;
        others += a.others();
    }
    (residue, others)
}

#[test]
fn every_road_equals_its_own_hifi_bit_for_bit() {
    for tracks in [Tracks::Correlated, Tracks::Independent] {
        let roads = roads(tracks);
        for car in cars() {
            let (residue, others) = assert_same(&car, &roads, true);
            println!(
                "{} {tracks:?}: {residue} residue, {others} fallbacks",
                car.name
            );
            assert!(residue > 0, "{}", car.name);
            if car.name == common::twin_axle_car().name && car.a == car.b {
                // Its own design falls back on every road.
                assert!(others >= roads.len() as u64, "{others}");
            }
        }
    }
}

#[test]
fn a_road_warp_and_mixed_tracks_go_road_by_road() {
    let mut warp = Car::datum();
    warp.track_front = 1.522;
    warp.track_rear = 1.510;
    let roads = roads(Tracks::Independent);
    // The residue route is built but errs at every point (the static gains of a track
    // do not sum to zero): every road takes its own exact routes.
    let (residue, others) = assert_same(&warp, &roads[..16], true);
    assert_eq!(residue, 0);
    // Each design twice (evaluate_routed and evaluate) on 16 roads.
    assert_eq!(others, 2 * 16 * designs(&warp).len() as u64);
    let many = HiFiRoads::new(&warp, &roads[..1]).unwrap();
    let r = many.evaluate_routed(20_000.0, 1_500.0).remove(0).unwrap();
    assert_eq!(r.route, HiFiRoute::Spectral);
    // One car, correlated and independent tracks: two models, each road on its own.
    let mixed = [Road::default(), roads[9]];
    assert_same(&Car::datum(), &mixed, false);
}

/// The ISO 8608 class scales the road velocity's intensity alone: at one speed the
/// criteria scale by `sqrt(Gd / Gd_B)` (1e-12 relative, against class B).
#[test]
fn the_class_only_scales_the_criteria() {
    let car = Car::datum();
    for tracks in [Tracks::Correlated, Tracks::Independent] {
        for speed in [5.0, 20.0, 40.0] {
            let at = |class| Road {
                class,
                speed,
                tracks,
            };
            let b = HiFi::new(&car, &at(RoadClass::B)).unwrap();
            for class in RoadClass::ALL {
                let h = HiFi::new(&car, &at(class)).unwrap();
                let scale = (class.gd_n0() / RoadClass::B.gd_n0()).sqrt();
                for (ks, cs) in designs(&car) {
                    let (c, cb) = (h.evaluate(ks, cs).unwrap(), b.evaluate(ks, cs).unwrap());
                    for (x, y) in c.to_array().iter().zip(cb.to_array()) {
                        let e = (x / (scale * y) - 1.0).abs();
                        assert!(e <= 1e-12, "{class:?} {speed} ({ks}, {cs}): {e:e}");
                    }
                }
            }
        }
    }
}

#[test]
fn bad_input_names_the_field() {
    let car = Car::datum();
    let e = HiFiRoads::new(&car, &[]).unwrap_err().to_string();
    assert!(e.starts_with("roads: "), "{e}");
    let bad = Road {
        speed: 0.0,
        ..Road::default()
    };
    let e = HiFiRoads::new(&car, &[Road::default(), bad])
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("speed: "), "{e}");
    let many = HiFiRoads::new(&car, &roads(Tracks::Correlated)[..3]).unwrap();
    for (ks, cs, field) in [(0.0, 1000.0, "ks"), (20_000.0, f64::NAN, "cs")] {
        let got = many.evaluate_routed(ks, cs);
        assert_eq!(got.len(), 3);
        for r in got {
            let e = r.unwrap_err().to_string();
            assert!(e.starts_with(&format!("{field}: ")), "{e}");
        }
    }
}
