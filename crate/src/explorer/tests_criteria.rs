//! The explorer's comfort measure and pick rule (issue #16): the session's Wk maps, front
//! and pick against the core's own routes, and bad values named.

use super::*;
use crate::analysis::ModelKind;
use crate::comfort::{Comfort, WkComfort};
use crate::criteria::bacc_wk_exact;
use crate::dos::Objective;
use crate::evaluate::Evaluator;
use crate::maps::dos_mask::objective_bit;
use crate::optimize::{normalised_distances, pick, pseudo_weights, recheck, PickRule};

fn session(patch: impl FnOnce(&mut State)) -> Session {
    let mut s = State::default();
    patch(&mut s);
    Session::new(s).unwrap()
}

/// With Wk comfort the LoFi and HiFi maps' first plane is the Wk-weighted RMS body
/// acceleration: at a few cells it equals the Kronecker route of `criteria` (the second
/// exact route behind `comfort.rs`'s modal one) to 1e-10 relative, and the evaluator's
/// `WkComfort::bacc_wk` bit for bit; DTL and SWS are the plain map's bit for bit; "BAcc no
/// worse than the datum" compares the cell's Wk with the datum's Wk.
#[test]
fn the_wk_map_plane_is_the_exact_wk_route() {
    let nw = |s: &mut State| s.no_worse = Some([true, false, false]);
    let mut wk = session(|s| {
        nw(s);
        s.comfort = Some("wk".into());
    });
    let mut plain = session(nw);
    let sc = wk.scenario().clone();
    assert_eq!(sc.comfort, Comfort::Wk);
    for (model, kind, nx, ny) in [
        (Model::LoFi, ModelKind::Quarter, 6, 5),
        (Model::HiFi, ModelKind::Full, 4, 3),
    ] {
        let m = wk.map(model, nx, ny).unwrap();
        let p = plain.map(model, nx, ny).unwrap();
        let n = nx * ny;
        let (mv, pv) = (m.planes(), p.planes());
        assert_eq!(mv[n..], pv[n..], "{model:?}: DTL and SWS planes");
        let slot = match kind {
            ModelKind::Quarter => WkComfort::quarter(&sc.datum, &sc.road),
            ModelKind::Full => WkComfort::full(sc.hifi().unwrap()),
        };
        let datum_wk = slot
            .bacc_wk(sc.datum.front.spring, sc.datum.front.damper)
            .unwrap();
        assert_eq!(m.values.datum.criteria.bacc, datum_wk);
        let bit = objective_bit(Objective::BaccDatum);
        let mut broken = 0;
        for (i, j) in [
            (0, 0),
            (nx - 1, 0),
            (nx / 2, ny / 2),
            (0, ny - 1),
            (nx - 1, ny - 1),
        ] {
            let (ks, cs) = m.grid().point(i, j);
            let k = j * nx + i;
            let car = sc.datum.with_front(ks, cs).unwrap();
            let exact = bacc_wk_exact(&kind.build(&car), &sc.road).unwrap();
            assert!(
                (mv[k] / exact - 1.0).abs() < 1e-10,
                "{model:?} ({i}, {j}): {} vs {exact}",
                mv[k]
            );
            assert_eq!(mv[k], slot.bacc_wk(ks, cs).unwrap());
            // Wk is smaller than the unweighted BAcc (|Wk| < 1 over most of the band).
            assert!(mv[k] < pv[k], "{model:?} ({i}, {j})");
            let worse = mv[k] > datum_wk;
            assert_eq!(m.broken()[k] & bit != 0, worse, "{model:?} ({i}, {j})");
            broken += usize::from(worse);
        }
        assert!(
            broken > 0 && broken < 5,
            "{model:?}: {broken} of 5 worse than the datum"
        );
    }
    // The surrogate is fitted to the unweighted BAcc: its map is the same under Wk.
    assert_eq!(
        wk.map(Model::Surrogate, 5, 4).unwrap().planes(),
        plain.map(Model::Surrogate, 5, 4).unwrap().planes()
    );
    // The criteria of the design by the LoFi and HiFi carry Wk.
    let (ks, cs) = (sc.design.front.spring, sc.design.front.damper);
    let c = wk.criteria(Model::HiFi).unwrap();
    assert_eq!(
        c.bacc,
        WkComfort::full(sc.hifi().unwrap()).bacc_wk(ks, cs).unwrap()
    );
}

/// The session's knee and weighted picks are `minmax::pick` of the rule on the same front
/// against the same datum, exactly, re-checked on the HiFi; every front point's
/// pseudo-weights are `pseudo_weights` of its normalised distances; the front itself does
/// not depend on the rule.
#[test]
fn the_sessions_pick_is_the_rules_pick_on_its_front() {
    let base = session(|_| {}).front("stm", Model::Surrogate).unwrap();
    assert_eq!(base.study.pick.rule, "minmax");
    for rule in ["knee", "asf:0.3", "asf:0.8"] {
        let mut x = session(|s| s.pick = Some(rule.into()));
        let r = x.front("stm", Model::Surrogate).unwrap();
        assert_eq!(r.study.front, base.study.front, "{rule}");
        let want = pick(&r.study.front, &r.datum, rule.parse::<PickRule>().unwrap()).unwrap();
        assert_eq!(r.study.pick, want, "{rule}");
        assert_eq!(r.study.pick.rule, rule);
        let hifi = x.scenario().hifi().unwrap();
        assert_eq!(r.recheck, recheck(&want, &hifi, &r.datum_hifi).unwrap());
        let d = normalised_distances(&r.study.front, &r.datum);
        assert_eq!(r.pseudo_weights.len(), r.study.front.len());
        for (w, d) in r.pseudo_weights.iter().zip(&d) {
            assert_eq!(*w, pseudo_weights(*d));
            assert!((w[0] + w[1] - 1.0).abs() < 1e-12);
        }
        assert_eq!(r.pseudo_weights[want.index], want.pseudo_weights);
    }
    // The knee and a comfort-heavy weight pick other designs than min-max on this front.
    let knee = session(|s| s.pick = Some("asf:0.9".into()))
        .front("stm", Model::Surrogate)
        .unwrap();
    assert!(
        knee.study.pick.index < base.study.pick.index,
        "W = 0.9 favours comfort"
    );
}

/// With Wk comfort the front is the LoFi's with Wk in the comfort slot, picked and
/// re-checked on the HiFi with Wk: the front equals the study on `WkComfort::quarter`,
/// the re-check the Wk HiFi at the pick; the surrogate's front is refused naming `comfort`.
#[test]
fn the_wk_front_is_the_lofis_and_is_rechecked_with_wk() {
    let mut x = session(|s| {
        s.comfort = Some("wk".into());
        s.pick = Some("knee".into());
    });
    let sc = x.scenario().clone();
    let r = x.front("stm", Model::LoFi).unwrap();
    assert_eq!(r.comfort, Comfort::Wk);
    let lofi = WkComfort::quarter(&sc.datum, &sc.road);
    for p in r.study.front.iter().step_by(7) {
        let c = lofi.evaluate(p.ks, p.cs).unwrap();
        assert_eq!((p.bacc, p.dtl, p.sws), (c.bacc, c.dtl, c.sws));
    }
    let hifi = WkComfort::full(sc.hifi().unwrap());
    let at = hifi.evaluate(r.study.pick.ks, r.study.pick.cs).unwrap();
    assert_eq!(r.recheck.rechecked, at);
    assert_eq!(
        r.datum_hifi,
        hifi.evaluate(sc.datum.front.spring, sc.datum.front.damper)
            .unwrap()
    );
    assert_eq!(
        r.study.pick,
        pick(&r.study.front, &r.datum, PickRule::Knee).unwrap()
    );
    match x.front("stm", Model::Surrogate) {
        Err(crate::RideError::Field { field, .. }) => assert_eq!(field, "comfort"),
        other => panic!("{:?}", other.map(|r| r.study.pick)),
    }
}

/// Bad comfort and pick values name their field and leave the session as it was; a state
/// without the two fields (an older link or session) reads as BAcc and min-max.
#[test]
fn bad_comfort_and_pick_name_their_field() {
    let field = |comfort: Option<&str>, pick: Option<&str>| {
        let s = State {
            comfort: comfort.map(Into::into),
            pick: pick.map(Into::into),
            ..State::default()
        };
        match s.scenario().unwrap_err() {
            crate::RideError::Field { field, reason } => format!("{field}: {reason}"),
            e => panic!("{e}"),
        }
    };
    assert_eq!(
        field(Some("iso"), None),
        "comfort: 'iso' is not 'bacc' or 'wk'"
    );
    assert_eq!(
        field(None, Some("best")),
        "pick: 'best' is not minmax, knee or asf:W"
    );
    assert!(field(None, Some("asf:1.5")).starts_with("pick: 'asf:1.5': the comfort weight"));
    assert!(field(None, Some("asf:x")).starts_with("pick: "));
    let mut x = session(|_| {});
    let before = x.state().clone();
    let bad = State {
        pick: Some("asf:-0.1".into()),
        ..before.clone()
    };
    assert!(x.set_state(bad).is_err());
    assert_eq!(x.state(), &before);
    // Older states: no comfort, no pick.
    let mut v = serde_json::to_value(State::default()).unwrap();
    let o = v.as_object_mut().unwrap();
    o.remove("comfort");
    o.remove("pick");
    let old: State = serde_json::from_value(v).unwrap();
    let sc = old.scenario().unwrap();
    assert_eq!((sc.comfort, sc.pick), (Comfort::Bacc, PickRule::MinMax));
    assert_eq!(ui_field("comfort"), "comfort");
    assert_eq!(ui_field("pick"), "pick");
}
