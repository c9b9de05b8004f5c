//! The session on a measured road (#31, the page's road menu): its maps are `ridelab map
//! --road FILE`'s, its readout and criteria `ridelab eval --road FILE`'s
//! ([`DesignOnRoad`]), its surrogate the fit of `ridelab surrogate --road FILE`; what runs
//! on ISO classes only is refused naming `road`.

use super::*;
use crate::analysis::ModelKind;
use crate::comfort::Comfort;
use crate::dos::DesignObjectives;
use crate::evaluate::Evaluator;
use crate::maps::{Grid, Scale};
use crate::road::Road;
use crate::road::Tracks;
use crate::road_profile::{DesignOnRoad, Profile, ProfileTracks, ShapedRoad};
use crate::study::measured::measured_map;
use crate::study::MapRequest;
use crate::study::MapSettings;
use crate::surrogate::{sample_plan, LmOptions};
use crate::time_domain::TimeOptions;
use std::rc::Rc;
use std::sync::Arc;

const SLAB: &str = "concrete-slab-5m.csv";

/// The shipped slab-road profile.
fn slab() -> Profile {
    let path = format!("{}/../assets/roads/{SLAB}", env!("CARGO_MANIFEST_DIR"));
    Profile::from_csv_bytes(&std::fs::read(path).unwrap()).unwrap()
}

/// A resolver of the key "slab" (the slab profile), as the page's `useRoad` registers one.
fn roads() -> RoadResolver {
    let profile = slab();
    let profile = Arc::new(profile);
    Rc::new(move |key: &str, speed: f64, tracks: Tracks| {
        assert_eq!(key, "slab");
        let t = ProfileTracks::on_page(&profile, tracks);
        let road = ShapedRoad::from_profile(&profile, speed, t)?;
        Ok(Arc::new(OnRoad::new(SLAB, 1, Arc::clone(&profile), road, t)) as Arc<dyn RoadSource>)
    })
}

fn on_slab() -> State {
    State {
        road_profile: Some("slab".into()),
        ..State::default()
    }
}

/// The LoFi and HiFi maps (both comfort measures) are `measured_map`'s, the CLI's `map
/// --road`, bit for bit; so is the datum; the objectives' mask is the same.
#[test]
fn maps_on_a_measured_road_are_the_clis() {
    let (nx, ny) = (24, 18);
    for comfort in ["bacc", "wk"] {
        let state = State {
            comfort: Some(comfort.into()),
            speed: 25.0,
            ..on_slab()
        };
        let mut x = Session::with_roads(state, Some(roads())).unwrap();
        let s = x.scenario().clone();
        let profile = slab();
        let road = ShapedRoad::from_profile(&profile, 25.0, ProfileTracks::Correlated).unwrap();
        for (model, kind) in [
            (Model::LoFi, ModelKind::Quarter),
            (Model::HiFi, ModelKind::Full),
        ] {
            let m = x.map(model, nx, ny).unwrap();
            let settings = MapSettings {
                grid: Grid::cells(&s.dbox, nx, ny).unwrap(),
                scale: Scale::Absolute,
                objectives: DesignObjectives::default(),
                contour_levels: 0,
                comfort: s.comfort,
            };
            // The ISO road is only recorded: the measured one replaces it.
            let iso = Road::default();
            let request = MapRequest::new(kind, &s.datum, &iso, settings);
            let cli = measured_map(&request, &road, SLAB, ProfileTracks::Correlated).unwrap();
            let want: Vec<f64> = [cli.bacc, cli.dtl, cli.sws].concat();
            assert_eq!(m.planes(), want, "{comfort} {kind:?}");
            assert_eq!(m.values.datum.criteria, cli.datum.criteria);
            assert_eq!(m.broken(), cli.feasibility.mask, "{comfort} {kind:?}");
        }
    }
}

/// The design's readout and criteria by both models are `ridelab eval --road`'s
/// ([`DesignOnRoad`]) bit for bit, Wk included; the report's frequency route on the raw
/// PSD agrees with the exact route to its tolerance; the describe-able road is the file.
#[test]
fn readout_on_a_measured_road_is_eval_road() {
    let state = State {
        ks: 24_000.0,
        cs: 1_900.0,
        ..on_slab()
    };
    let mut x = Session::with_roads(state, Some(roads())).unwrap();
    let s = x.scenario().clone();
    let road = ShapedRoad::from_profile(&slab(), 20.0, ProfileTracks::Correlated).unwrap();
    let on = DesignOnRoad::on_shaped(
        &s.datum,
        24_000.0,
        1_900.0,
        &road,
        SLAB,
        ProfileTracks::Correlated,
    )
    .unwrap();
    for (kind, model, want, wk) in [
        (
            ModelKind::Quarter,
            Model::LoFi,
            on.quarter,
            on.bacc_wk.quarter,
        ),
        (ModelKind::Full, Model::HiFi, on.full, on.bacc_wk.full),
    ] {
        let r = x.readout(kind).unwrap();
        assert_eq!([r.bacc, r.dtl, r.sws], want.to_array(), "{kind:?}");
        assert_eq!(r.bacc_wk, wk);
        assert_eq!(x.criteria(model).unwrap(), want);
        let rep = x.report(kind).unwrap();
        assert_eq!([rep.bacc, rep.dtl, rep.sws], want.to_array());
        assert!(
            rep.route_difference.unwrap() < 0.03,
            "{kind:?}: {:?}",
            rep.route_difference
        );
        assert!(matches!(rep.road, crate::road::RoadScenario::Measured(ref m) if m.file == SLAB));
    }
}

/// The surrogate is fitted to the full car's samples on the road with the quarter car
/// there as its LoFi (`ridelab surrogate --road`'s fit): the same predictions bit for
/// bit; a measured road changes the fit key, the ISO class under it does not matter.
#[test]
fn the_surrogate_on_a_measured_road_is_the_clis() {
    let mut x = Session::with_roads(on_slab(), Some(roads())).unwrap();
    let s = x.scenario().clone();
    let m = s.measured.as_ref().unwrap();
    let setting = m.0.setting(&s.datum, &s.dbox).unwrap();
    let hifi = m.0.evaluator(ModelKind::Full, &s.datum, Comfort::Bacc);
    let samples = sample_plan(&hifi, &s.plan.plan().unwrap(), &s.dbox).unwrap();
    let cli = s
        .surrogate
        .fit(&setting, &samples, &LmOptions::default())
        .unwrap();
    let fitted = x.surrogate().unwrap();
    for (ks, cs) in [(18_000.0, 1_000.0), (30_000.0, 2_600.0)] {
        assert_eq!(
            fitted.model.evaluate(ks, cs).unwrap(),
            cli.evaluate(ks, cs).unwrap()
        );
    }
    assert_eq!(x.fit_count(), 1);
    let iso = State::default().scenario().unwrap();
    assert_ne!(FitKey::of(&s), FitKey::of(&iso));
    // ... and the design's report (FIT_FIELDS and REPORT_FIELDS hold `roadProfile`).
    let on_iso = crate::analysis::report(ModelKind::Quarter, &iso.design, &iso.road).unwrap();
    let on_road = x.report(ModelKind::Quarter).unwrap();
    assert_ne!(on_road.bacc, on_iso.bacc);
    assert_ne!(on_road.road, on_iso.road);
    assert!(FIT_FIELDS.contains(&"roadProfile") && REPORT_FIELDS.contains(&"roadProfile"));
    // Another class under the measured road: the same road, the same fit.
    x.set_state(State {
        class: "E".into(),
        ..on_slab()
    })
    .unwrap();
    assert_eq!(FitKey::of(x.scenario()), FitKey::of(&s));
    // The speed shapes the road again.
    x.set_state(State {
        speed: 30.0,
        ..on_slab()
    })
    .unwrap();
    assert_ne!(FitKey::of(x.scenario()), FitKey::of(&s));
}

/// What runs on ISO classes only is refused: the GPU path's values naming `road`, robust
/// cases naming `cases`, and a road no resolver knows naming `road`; the session keeps
/// its last good state.
#[test]
fn a_measured_road_refuses_what_it_cannot_run() {
    let mut x = Session::with_roads(on_slab(), Some(roads())).unwrap();
    let field = |e: crate::error::RideError| match e {
        crate::error::RideError::Field { field, .. } => field,
        other => panic!("{other}"),
    };
    assert_eq!(
        field(x.hifi_front(Some(&[1.0; 3 * 61 * 61])).unwrap_err()),
        "road"
    );
    assert_eq!(
        field(x.keep_hifi_planes(2, 2, &[1.0; 12]).unwrap_err()),
        "road"
    );
    let with_cases = State {
        cases: Some(r#"{"operating": [{"class": "C", "speed": 25}]}"#.into()),
        ..on_slab()
    };
    assert_eq!(field(x.set_state(with_cases).unwrap_err()), "cases");
    assert_eq!(x.state(), &on_slab());
    assert_eq!(field(Session::new(on_slab()).err().unwrap()), "road");
    // Back to the class: the ISO road again.
    x.set_state(State::default()).unwrap();
    assert!(x.scenario().measured.is_none());
    x.keep_hifi_planes(2, 2, &[1.0; 12]).unwrap();
}

/// The HiFi front on a measured road is `ridelab optimize --road FILE --evaluator full
/// --grid 61 --levels 2`'s bit for bit (front, hypervolume, pick), as on an ISO road.
#[test]
fn the_hifi_front_on_a_measured_road_is_optimize_road() {
    use crate::optimize::Method;
    use crate::road_profile::MeasuredModel;
    use crate::study::measured::optimize_measured;
    use crate::study::{EvaluatorSpec, OptimizeRequest};
    let mut x = Session::with_roads(on_slab(), Some(roads())).unwrap();
    let view = x.hifi_front(None).unwrap();
    let s = x.scenario().clone();
    let road = ShapedRoad::from_profile(&slab(), 20.0, ProfileTracks::Correlated).unwrap();
    let hifi = MeasuredModel::new(ModelKind::Full, &s.datum, road);
    let request = OptimizeRequest {
        evaluator: EvaluatorSpec::Model(ModelKind::Full),
        ..OptimizeRequest::new(
            &s.datum,
            &s.road,
            s.dbox,
            Method::Stm(crate::optimize::StmParams {
                grid: 61,
                levels: 2,
            }),
            s.objectives.clone(),
        )
    };
    let (cli, _) = optimize_measured(&request, &hifi, None).unwrap();
    let f = &view.front.study;
    assert_eq!(f.front.len(), cli.study.front.len());
    for (a, b) in f.front.iter().zip(&cli.study.front) {
        assert_eq!(
            [a.ks, a.cs, a.bacc, a.dtl, a.sws],
            [b.ks, b.cs, b.bacc, b.dtl, b.sws]
        );
    }
    assert_eq!(f.hypervolume, cli.study.hypervolume);
    assert_eq!(
        (f.pick.ks, f.pick.cs),
        (cli.study.pick.ks, cli.study.pick.cs)
    );
}

/// The spectra on a measured road: the PSDs are the measured road's (their area over
/// 0.1..100 Hz is the design's variance by the frequency route on the raw PSD, the
/// report's check, less what lies outside the band: within 1 % for BAcc and SWS, 2 % for
/// DTL, whose tyre-deflection tail above 100 Hz holds about 2.7 % of its variance,
/// METHOD.md), the FRFs the ISO road's (a transfer does not depend on the roughness).
#[test]
fn spectra_on_a_measured_road_hold_the_criteria() {
    let mut x = Session::with_roads(on_slab(), Some(roads())).unwrap();
    let sp = x.spectra(4000).unwrap();
    let mut iso = Session::new(State::default()).unwrap();
    let isp = iso.spectra(4000).unwrap();
    for (name, m, kind) in [
        ("lofi", &sp.lofi, ModelKind::Quarter),
        ("hifi", &sp.hifi, ModelKind::Full),
    ] {
        let r = x.report(kind).unwrap().spectral.unwrap();
        let area = |p: &[f64]| -> f64 {
            sp.f.windows(2)
                .zip(p.windows(2))
                .map(|(f, p)| 0.5 * (p[0] + p[1]) * (f[1] - f[0]))
                .sum()
        };
        for (o, (want, tol)) in r.to_array().into_iter().zip([0.01, 0.02, 0.01]).enumerate() {
            let got = area(&m.psd[o]).sqrt();
            assert!(
                (got / want - 1.0).abs() < tol,
                "{name} output {o}: {got} against {want}"
            );
        }
        let ifr = if name == "lofi" { &isp.lofi } else { &isp.hifi };
        assert_eq!(m.frf, ifr.frf, "{name}: the FRFs are the ISO road's");
        assert_ne!(m.psd, ifr.psd);
    }
}

/// The time response on a measured road is the profile played back from rest: the first
/// `duration` seconds of `ridelab simulate --road FILE`'s run over the whole profile, bit
/// for bit, for both models.
#[test]
fn the_time_response_on_a_measured_road_is_the_playback() {
    use crate::road_profile::playback;
    use crate::time_domain::simulate_playback;
    let x = Session::with_roads(on_slab(), Some(roads())).unwrap();
    let opt = TimeOptions {
        duration: 4.0,
        decimate: 10,
        ..TimeOptions::default()
    };
    let r = x.time_response(&opt).unwrap();
    let s = x.scenario();
    let profile = slab();
    for (kind, got) in [(ModelKind::Quarter, &r.lofi), (ModelKind::Full, &r.hifi)] {
        // As the CLI: the whole profile at the largest step at most dt that divides it.
        let dt = profile.playback_step(20.0, opt.dt);
        let road = playback(&profile, &kind.build(&s.design).wheels, 20.0, dt).unwrap();
        let whole = TimeOptions {
            dt,
            duration: (road.len() - 1) as f64 * dt,
            ..opt
        };
        // Its first 2 000 steps are enough to compare (the full run is 150 s).
        let head: Vec<Vec<f64>> = road.wheels.iter().map(|w| w[..6001].to_vec()).collect();
        let want = simulate_playback(
            kind,
            &s.design,
            dt,
            &head,
            &TimeOptions {
                duration: 6000.0 * dt,
                ..whole
            },
        )
        .unwrap();
        let n = got.t.len();
        assert!(
            n > 300 && (got.t[n - 1] - 4.0).abs() < dt * 10.0,
            "{kind:?}: {n} samples to {}",
            got.t[n - 1]
        );
        assert_eq!(got.t[..], want.t[..n]);
        for o in 0..3 {
            assert_eq!(
                got.outputs[o][..],
                want.outputs[o][..n],
                "{kind:?} output {o}"
            );
        }
    }
}

/// The page's adaptive loop on a measured road is `ridelab surrogate --road FILE
/// --adaptive K`'s (the study's loop with the full car there as its HiFi and the quarter
/// car there as the surrogate's LoFi): the same samples, reasons, fronts and picks.
#[test]
fn the_adaptive_loop_on_a_measured_road_is_the_clis() {
    use crate::road_profile::MeasuredModel;
    use crate::study::adaptive::{run, AdaptiveOptions, Decision};
    use crate::surrogate::{PlanSpec, Setting, SurrogateSpec};
    let state = State {
        surrogate: Some("gp-mul".into()),
        plan: Some("ae:5".into()),
        ..on_slab()
    };
    let x = Session::with_roads(state, Some(roads())).unwrap();
    let sc = x.scenario();
    let options = AdaptiveOptions {
        runs: 2,
        candidates: 11,
        ..AdaptiveOptions::default()
    };
    let mut page = PageLoop::new(sc, options).unwrap();
    for _ in 0..2 {
        page.step().unwrap();
    }
    let road = ShapedRoad::from_profile(&slab(), 20.0, ProfileTracks::Correlated).unwrap();
    let setting = Setting::measured(&sc.datum, road.clone(), &sc.dbox).unwrap();
    let hifi = MeasuredModel::new(ModelKind::Full, &sc.datum, road);
    let cli = run(
        SurrogateSpec::parse("gp-mul").unwrap(),
        &setting,
        &hifi,
        PlanSpec::AudzeEglais(5),
        &Decision::of_car(&sc.datum, &hifi).unwrap(),
        options,
    )
    .unwrap();
    assert_eq!(page.report(), cli.report());
    assert_eq!(page.front(), cli.front());
}
