//! The domain of validity (issue #27): every car, design and road inside it gives finite,
//! positive criteria that two independent routes agree on, and everything outside it is
//! refused naming the field. Cars are drawn log-uniformly over the whole domain
//! (`ridelab::domain`), corners included, so the ranges the README states are the ranges
//! the numerics were shown to hold over.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use ridelab::analysis::report;
use ridelab::car::{Axle, Car};
use ridelab::criteria::criteria_exact;
use ridelab::domain::{self, Limit};
use ridelab::road::{Road, RoadClass, Tracks};
use ridelab::{Evaluator, HiFi, LoFi, ModelKind};

/// Log-uniform in a limit's range (uniform where it starts at 0).
fn draw(rng: &mut ChaCha8Rng, l: &Limit) -> f64 {
    if l.min <= 0.0 {
        return rng.random_range(l.min..=l.max);
    }
    (rng.random_range(l.min.ln()..=l.max.ln()))
        .exp()
        .clamp(l.min, l.max)
}

/// One end of a limit or the other.
fn end(rng: &mut ChaCha8Rng, l: &Limit) -> f64 {
    if rng.random_bool(0.5) {
        l.min
    } else {
        l.max
    }
}

/// A car anywhere in the domain; `corner` puts every parameter at an end of its range.
fn car(rng: &mut ChaCha8Rng, corner: bool) -> Car {
    let mut v = |l: &Limit| if corner { end(rng, l) } else { draw(rng, l) };
    let mut axle = || Axle {
        unsprung_mass: v(&domain::UNSPRUNG_MASS),
        spring: v(&domain::SPRING),
        damper: v(&domain::DAMPER),
        tire_stiffness: v(&domain::TIRE_STIFFNESS),
        tire_damping: v(&domain::TIRE_DAMPING),
    };
    let (front, rear) = (axle(), axle());
    let m = v(&domain::SPRUNG_MASS);
    let (a, b) = (v(&domain::AXLE_DISTANCE), v(&domain::AXLE_DISTANCE));
    let (tf, tr) = (v(&domain::TRACK), v(&domain::TRACK));
    let half = (tf + tr) / 4.0;
    Car {
        name: "domain".into(),
        source: "tests/domain.rs".into(),
        sprung_mass: m,
        pitch_inertia: v(&domain::DYNAMIC_INDEX) * m * a * b,
        roll_inertia: v(&domain::ROLL_INDEX) * m * half * half,
        a,
        b,
        track_front: tf,
        track_rear: tr,
        front,
        rear,
    }
}

fn road(rng: &mut ChaCha8Rng) -> Road {
    Road {
        class: RoadClass::ALL[rng.random_range(0..8)],
        speed: draw(rng, &domain::SPEED),
        tracks: if rng.random_bool(0.5) {
            Tracks::Correlated
        } else {
            Tracks::Independent
        },
    }
}

/// 300 cars of the domain (200 drawn log-uniformly, 100 with every parameter at an end of
/// its range; drawn until the domain accepts them) on random roads: both models' reports
/// are finite and > 0; the frequency route agrees with the exact route within its own
/// stated error everywhere and to 1e-6 where it converged to 1e-8; the Kronecker route
/// and the evaluators (the maps' residue route) give the report's criteria to 1e-7.
#[test]
fn every_car_in_the_domain_gives_finite_criteria_that_two_routes_agree_on() {
    let mut rng = ChaCha8Rng::seed_from_u64(27);
    let mut worst = (0.0f64, String::new());
    let (mut worst_eval, mut worst_kron, mut tight) = (0.0f64, 0.0f64, 0usize);
    let (mut drawn, mut k) = (0usize, 0usize);
    while k < 300 {
        // Each parameter in its own range; the car's corners (mass ratio, wheel hop,
        // bounce, damping) decide whether it is in the domain: only those that are count.
        let corner = k >= 200;
        let c = car(&mut rng, corner);
        drawn += 1;
        assert!(
            drawn < 200_000,
            "only {k} cars in the domain after {drawn} draws"
        );
        if c.validate().is_err() {
            continue;
        }
        k += 1;
        let r = road(&mut rng);
        for kind in [ModelKind::Quarter, ModelKind::Full] {
            let rep = report(kind, &c, &r)
                .unwrap_or_else(|e| panic!("car {k} ({kind:?}, {r:?}): {e}\n{}", c.to_json()));
            // The frequency route agrees within its own stated error (it runs out of
            // panels first where modes sit decades apart, and says so).
            let estimate = rep
                .spectral_error_estimate
                .expect("an ISO report is checked");
            let allowed = (10.0 * estimate).max(1e-7);
            let difference = rep.route_difference.unwrap_or(0.0);
            assert!(
                difference <= allowed,
                "car {k} {kind:?} {r:?}: routes differ by {:e}, the frequency route's estimate {:e}\n{}",
                difference,
                estimate,
                c.to_json()
            );
            if estimate < 1e-8 {
                tight += 1;
                if difference > worst.0 {
                    worst = (difference, format!("car {k} {kind:?} {r:?}"));
                }
            }
            // The Kronecker route, independent of the modal and residue routes.
            if let Ok(kron) = criteria_exact(&kind.build(&c), &r) {
                for (x, y) in kron.to_array().iter().zip([rep.bacc, rep.dtl, rep.sws]) {
                    worst_kron = worst_kron.max((x / y - 1.0).abs());
                }
            }
            let e: Box<dyn Evaluator> = match kind {
                ModelKind::Quarter => Box::new(LoFi::new(&c, &r)),
                ModelKind::Full => Box::new(HiFi::new(&c, &r).unwrap()),
            };
            let got = e.evaluate(c.front.spring, c.front.damper).unwrap();
            for (x, y) in got.to_array().iter().zip([rep.bacc, rep.dtl, rep.sws]) {
                worst_eval = worst_eval.max((x / y - 1.0).abs());
            }
        }
    }
    // Where the frequency route converged to 1e-8, the exact route is within 1e-6 of it.
    assert!(
        worst.0 < 1e-6,
        "exact vs frequency route: {:e} at {}",
        worst.0,
        worst.1
    );
    assert!(
        tight >= 300,
        "only {tight} of 600 reports converged to 1e-8"
    );
    // The modal route (the report's) loses a few digits at the domain's far corners (a
    // 20 t body on a 0.4 m wheelbase: 6e-8); the Kronecker and residue routes agree to
    // 1e-12 there.
    assert!(worst_kron < 1e-7, "modal vs Kronecker: {worst_kron:e}");
    assert!(worst_eval < 1e-7, "evaluator vs report: {worst_eval:e}");
    eprintln!(
        "domain sweep: 300 cars in the domain of {drawn} drawn; {tight} of 600 frequency routes converged to 1e-8, worst difference there {:e} ({}); modal vs Kronecker {worst_kron:e}; evaluator {worst_eval:e}",
        worst.0, worst.1
    );
}

/// One past each end of every car parameter's range is refused, naming the field.
#[test]
fn one_step_outside_every_range_is_refused_naming_the_field() {
    let base = Car::datum();
    type Set = fn(&mut Car, f64);
    let fields: [(&str, &Limit, Set); 10] = [
        ("sprung_mass", &domain::SPRUNG_MASS, |c, v| {
            c.sprung_mass = v
        }),
        ("a", &domain::AXLE_DISTANCE, |c, v| c.a = v),
        ("b", &domain::AXLE_DISTANCE, |c, v| c.b = v),
        ("track_front", &domain::TRACK, |c, v| c.track_front = v),
        ("track_rear", &domain::TRACK, |c, v| c.track_rear = v),
        ("front.unsprung_mass", &domain::UNSPRUNG_MASS, |c, v| {
            c.front.unsprung_mass = v
        }),
        ("rear.spring", &domain::SPRING, |c, v| c.rear.spring = v),
        ("front.damper", &domain::DAMPER, |c, v| c.front.damper = v),
        ("rear.tire_stiffness", &domain::TIRE_STIFFNESS, |c, v| {
            c.rear.tire_stiffness = v
        }),
        ("front.tire_damping", &domain::TIRE_DAMPING, |c, v| {
            c.front.tire_damping = v
        }),
    ];
    for (field, limit, set) in fields {
        for v in [limit.min * 0.999 - 1e-9, limit.max * 1.001, f64::NAN, 1e300] {
            let mut c = base.clone();
            set(&mut c, v);
            // Keep the inertias in range when the mass or the geometry moves.
            if field == "sprung_mass" || field == "a" || field == "b" {
                c.pitch_inertia = c.sprung_mass * c.a.abs() * c.b.abs();
            }
            if field == "sprung_mass" || field.starts_with("track") {
                let h = (c.track_front + c.track_rear).abs() / 4.0;
                c.roll_inertia = 0.5 * c.sprung_mass * h * h;
            }
            let e = c
                .validate()
                .expect_err(&format!("{field} = {v}"))
                .to_string();
            assert!(e.starts_with(&format!("{field}: ")), "{field} = {v}: {e}");
        }
    }
    // The inertias through the body's indices: the 1e9 kg body is refused by
    // the mass, a heavy body with a car's inertia by the dynamic index.
    let mut c = base.clone();
    c.sprung_mass = 20_000.0;
    let e = c.validate().unwrap_err().to_string();
    assert!(
        e.starts_with("pitch_inertia: 2460 kg m^2 gives a pitch dynamic index"),
        "{e}"
    );
    assert!(e.contains("for this body 3645.67..182283 kg m^2"), "{e}");
}

/// The road and the design: speeds and designs outside their ranges are refused, the
/// issue's cases among them (`--speed 1e-320`, `--ks 1e12`, Cs 1e9 N s/m).
#[test]
fn speeds_and_designs_outside_are_refused() {
    for v in [1e-320, 0.5, 100.5, f64::INFINITY] {
        let r = Road {
            speed: v,
            ..Road::default()
        };
        let e = r.validate().unwrap_err().to_string();
        assert!(e.starts_with("speed: "), "{e}");
    }
    let hifi = HiFi::new(&Car::datum(), &Road::default()).unwrap();
    let lofi = LoFi::new(&Car::datum(), &Road::default());
    for (ks, cs, field) in [
        (1e12, 1_000.0, "ks"),
        (1e308, 1_000.0, "ks"),
        (999.0, 1_000.0, "ks"),
        (20_000.0, 1e9, "cs"),
        (20_000.0, 9.0, "cs"),
    ] {
        for e in [&hifi as &dyn Evaluator, &lofi] {
            let msg = e.evaluate(ks, cs).unwrap_err().to_string();
            assert!(msg.starts_with(&format!("{field}: ")), "{ks} {cs}: {msg}");
            assert!(
                !msg.contains("road warp") && !msg.contains("stable"),
                "{msg}"
            );
        }
    }
}

/// The README's table of the domain is the one the code checks (generated by
/// `cargo run --example domain_table`, pasted between its markers).
#[test]
fn the_readme_states_the_domain_the_code_checks() {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../README.md"))
        .expect("README.md");
    let start = readme
        .find("<!-- domain-table")
        .and_then(|i| readme[i..].find('\n').map(|j| i + j + 1))
        .expect("the README's domain-table marker");
    let end = readme
        .find("<!-- end domain-table -->")
        .expect("its end marker");
    assert_eq!(
        &readme[start..end],
        domain::markdown_table(),
        "regenerate the README's table: cargo run --example domain_table"
    );
}
