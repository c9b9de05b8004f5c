//! The modal route on a shaped road: the exact variances of [`criteria_shaped`] from the
//! model's modal expansion and the shaping filter's partial fractions, some tens of
//! microseconds a point instead of the augmented Lyapunov equations' milliseconds.
//!
//! The model's modal expansion ([`crate::criteria::criteria_modal`]) gives the transfer
//! from wheel group `g`'s road velocity to output `o` as
//! `T_g(s) / s = sum_k rho_gk / (s - lambda_k) + G_g / s`. A source's road velocity is
//! its filter `F(s) = K + sum_i c_i / (s - mu_i)` ([`ShapingFilter::partial_fractions`])
//! driven by unit white noise, so the transfer from that noise is the product, whose
//! partial fractions take each factor's residue times the other factor's value there:
//!
//! ```text
//! F(s) T_g(s) / s = sum_k rho_gk F(lambda_k) / (s - lambda_k)
//!                 + sum_i c_i (T_g(mu_i) / mu_i) / (s - mu_i) + F(0) G_g / s
//! ```
//!
//! (the filter's poles are real, stable and fixed by the road; the model's move with the
//! design). That is the modal route's form on the poles `lambda_k` and `mu_i` with static
//! gains `F(0) G_g`, so its closed form gives the variances, the front-rear delay exact,
//! with unit intensity; independent sources add. The expansion is checked against
//! `F(s) T_g(s) / s` at 3 Hz, and the route declines (`Err(ModalInapplicable(..))`, the
//! caller then takes [`criteria_shaped`]) where it is not accurate: the model's own
//! expansion declines, the filter's partial fractions cancel (nearly repeated poles,
//! [`crate::criteria::PoleZeroFilter::new`]), or a filter pole nearly meets a
//! (real) pole of the model, where the two fractions would cancel.

use super::exact::{bacc_wk_shaped, criteria_shaped};
use super::shaped::ShapedRoad;
use crate::criteria::{
    add_source_variances, add_wk_variance, expand_sources, inverse_sums, static_gain, Channel,
};
use crate::error::{Result, RideError};
use crate::evaluate::Criteria;
use crate::math;
use crate::model::{LinearModel, N_OUT};
use num_complex::Complex64 as C64;
use std::f64::consts::PI;

/// One source's part of the shaped expansion: the poles (the model's, then the filter's),
/// the wheel groups' delays (s) and static gains `F(0) G_g`, and the residues
/// `res[g][o][k]` of `F(s) T_g(s) / s` on the poles.
struct SourceExpansion {
    poles: Vec<C64>,
    groups: Vec<(f64, [f64; N_OUT])>,
    res: Vec<Vec<Vec<C64>>>,
}

/// The expansion of every source of `road` that drives a wheel of `model` (module doc),
/// checked at 3 Hz; `Err(ModalInapplicable(..))` where it is not accurate.
fn expansion(model: &LinearModel, road: &ShapedRoad) -> Result<Vec<SourceExpansion>> {
    road.validate()?;
    let channels: Vec<Vec<Channel>> = road
        .sources
        .iter()
        .map(|src| {
            model
                .wheels
                .iter()
                .enumerate()
                .map(|(j, wheel)| {
                    (
                        j,
                        wheel.behind / road.speed,
                        src.weights[wheel.track.min(1)],
                    )
                })
                .filter(|c| c.2 != 0.0)
                .collect()
        })
        .collect();
    let e = expand_sources(model, &channels, 1.0)?;
    let inapplicable = |why: &str| RideError::ModalInapplicable(why.into());
    let s0 = C64::new(0.0, 2.0 * PI * 3.0);
    let mut out = Vec::with_capacity(road.sources.len());
    for ((groups, rho), src) in e.sources.iter().zip(&road.sources) {
        if groups.is_empty() {
            continue;
        }
        let filter = &src.filter;
        let filter = filter
            .pole_zero()
            .ok_or_else(|| inapplicable("the shaping filter's partial fractions cancel"))?;
        let fractions = filter.fractions();
        for &(mu, _) in fractions {
            if e.lam
                .iter()
                .any(|&l| math::cabs(l - mu) <= 1e-6 * math::cabs(l))
            {
                return Err(inapplicable(
                    "a shaping filter pole meets a pole of the model",
                ));
            }
        }
        let poles: Vec<C64> = e
            .lam
            .iter()
            .copied()
            .chain(fractions.iter().map(|&(mu, _)| C64::new(mu, 0.0)))
            .collect();
        let f_lam: Vec<C64> = e.lam.iter().map(|&l| filter.at(l)).collect();
        let f0 = filter.dc_gain();
        let mut res = Vec::with_capacity(groups.len());
        for (g, r) in groups.iter().zip(rho) {
            let mut per_output = Vec::with_capacity(N_OUT);
            for (o, r) in r.iter().enumerate() {
                // T_g(s) / s from the model's expansion.
                let t_over_s = |s: C64| -> C64 {
                    r.iter()
                        .zip(&e.lam)
                        .map(|(&rk, &lk)| rk / (s - lk))
                        .sum::<C64>()
                        + g.g[o] / s
                };
                let rg: Vec<C64> = r
                    .iter()
                    .zip(&f_lam)
                    .map(|(&rk, &f)| rk * f)
                    .chain(
                        fractions
                            .iter()
                            .map(|&(mu, c)| c * t_over_s(C64::new(mu, 0.0))),
                    )
                    .collect();
                let direct = filter.at(s0) * t_over_s(s0);
                let modal: C64 = rg
                    .iter()
                    .zip(&poles)
                    .map(|(&r, &p)| r / (s0 - p))
                    .sum::<C64>()
                    + f0 * g.g[o] / s0;
                if math::cabs(direct - modal) > 1e-9 * math::cabs(direct).max(1e-300) {
                    return Err(inapplicable("shaped expansion check failed"));
                }
                per_output.push(rg);
            }
            res.push(per_output);
        }
        out.push(SourceExpansion {
            poles,
            groups: groups
                .iter()
                .map(|g| (g.tau, g.g.map(|v| f0 * v)))
                .collect(),
            res,
        });
    }
    Ok(out)
}

/// Exact RMS `[BAcc m/s^2, DTL N, SWS m]` of `model` on the shaped `road` by the modal
/// route (module doc); declines with `Err(ModalInapplicable(..))` where it is not
/// accurate. Refuses a white feed-through and a road warp as [`criteria_shaped`] does.
pub fn criteria_shaped_modal(model: &LinearModel, road: &ShapedRoad) -> Result<Criteria> {
    let mut var = [0.0; N_OUT];
    for s in expansion(model, road)? {
        let inv = inverse_sums(&s.poles);
        add_source_variances(&mut var, &s.poles, &inv, &s.groups, &s.res, 1.0);
    }
    if var.iter().any(|v| !v.is_finite() || *v <= 0.0) {
        return Err(RideError::ModalInapplicable(
            "a variance came out non-positive".into(),
        ));
    }
    Ok(Criteria::from_array(var.map(f64::sqrt)))
}

/// The ISO 2631-1 Wk-weighted RMS body acceleration above the front wheel of `model` on
/// the shaped `road`, m/s^2, by the modal route: the shaped expansion's BAcc fractions
/// (module doc) times the Wk filter's ([`crate::criteria::bacc_wk_modal`]'s closed form
/// on the model's, the road filters' and Wk's poles). Declines with
/// `Err(ModalInapplicable(..))` where either expansion is not accurate.
pub(crate) fn bacc_wk_shaped_modal(model: &LinearModel, road: &ShapedRoad) -> Result<f64> {
    let mut var = 0.0;
    for s in expansion(model, road)? {
        let scale = s
            .res
            .iter()
            .flat_map(|r| r[0].iter())
            .map(|r| math::cabs(*r))
            .fold(0.0, f64::max);
        if s.groups
            .iter()
            .any(|g| g.1[0].abs() > 1e-9 * scale.max(1e-300))
        {
            return Err(static_gain());
        }
        let taus: Vec<f64> = s.groups.iter().map(|g| g.0).collect();
        let bacc: Vec<&[C64]> = s.res.iter().map(|r| r[0].as_slice()).collect();
        add_wk_variance(&mut var, &s.poles, &taus, &bacc, 1.0)?;
    }
    if !var.is_finite() || var <= 0.0 {
        return Err(RideError::ModalInapplicable(
            "the weighted variance came out non-positive".into(),
        ));
    }
    Ok(var.sqrt())
}

/// The Wk-weighted RMS body acceleration on a shaped road, m/s^2, exact: the modal route
/// ([`bacc_wk_shaped_modal`]) where it is accurate, else the Lyapunov equations of the
/// model augmented with the road's filters and Wk ([`bacc_wk_shaped`]).
pub(crate) fn bacc_wk_shaped_fast(model: &LinearModel, road: &ShapedRoad) -> Result<f64> {
    match bacc_wk_shaped_modal(model, road) {
        Err(RideError::ModalInapplicable(_)) => bacc_wk_shaped(model, road),
        other => other,
    }
}

/// Exact criteria on a shaped road: the modal route ([`criteria_shaped_modal`]) where it
/// is accurate, the augmented Lyapunov equations ([`criteria_shaped`]) otherwise.
pub(crate) fn criteria_shaped_fast(model: &LinearModel, road: &ShapedRoad) -> Result<Criteria> {
    match criteria_shaped_modal(model, road) {
        Err(RideError::ModalInapplicable(_)) => criteria_shaped(model, road),
        other => other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::car::Car;
    use crate::model::{full_car, quarter_car};
    use crate::road::{Road, RoadClass, Tracks};
    use crate::road_profile::{shipped_examples, synthesize, ProfileTracks};

    /// The worst relative difference of two criteria.
    fn worst(a: Criteria, b: Criteria) -> f64 {
        a.to_array()
            .iter()
            .zip(b.to_array())
            .map(|(x, y)| (x / y - 1.0).abs())
            .fold(0.0, f64::max)
    }

    /// The modal route equals the Lyapunov route to 1e-9 (the Wk-weighted BAcc to 1e-7) on
    /// the quarter and the full car,
    /// with and without tyre damping, at designs across the box, on ISO roads of waviness
    /// 1.5 to 3.5 (correlated and independent tracks, three speeds) and on both shipped
    /// profiles (every track setting they take); and it declines nowhere there.
    #[test]
    fn the_modal_route_is_the_lyapunov_route() {
        let mut roads = Vec::new();
        for (w, class, speed, tracks) in [
            (1.5, RoadClass::B, 10.0, Tracks::Correlated),
            (2.5, RoadClass::C, 20.0, Tracks::Independent),
            (3.5, RoadClass::D, 35.0, Tracks::Correlated),
            (2.0, RoadClass::A, 25.0, Tracks::Independent),
        ] {
            let road = Road {
                class,
                speed,
                tracks,
            };
            roads.push(ShapedRoad::iso(&road, w).unwrap());
        }
        for (_, synthesis) in shipped_examples() {
            let profile = synthesize(&synthesis).unwrap();
            let both = [
                ProfileTracks::Correlated,
                ProfileTracks::Independent,
                ProfileTracks::Measured,
            ];
            for tracks in both
                .into_iter()
                .take(if profile.tracks() == 2 { 3 } else { 2 })
            {
                roads.push(ShapedRoad::from_profile(&profile, 22.0, tracks).unwrap());
            }
        }
        let mut car = Car::datum();
        let (mut max, mut max_wk) = (0.0_f64, 0.0_f64);
        let mut points = 0;
        for ct in [0.0, 150.0] {
            car.front.tire_damping = ct;
            car.rear.tire_damping = ct;
            for (ks, cs) in [(12e3, 600.0), (25e3, 1800.0), (38e3, 3900.0)] {
                let design = car.with_front(ks, cs).unwrap();
                for model in [quarter_car(&design.quarter()), full_car(&design)] {
                    for road in &roads {
                        let a = criteria_shaped_modal(&model, road).unwrap();
                        let b = criteria_shaped(&model, road).unwrap();
                        max = max.max(worst(a, b));
                        let wk_a = bacc_wk_shaped_modal(&model, road).unwrap();
                        let wk_b = bacc_wk_shaped(&model, road).unwrap();
                        max_wk = max_wk.max((wk_a / wk_b - 1.0).abs());
                        points += 1;
                    }
                }
            }
        }
        eprintln!("modal vs Lyapunov: worst {max:e} (Wk {max_wk:e}) over {points} points");
        assert!(points >= 100, "{points}");
        assert!(max < 1e-9, "worst relative difference {max:e}");
        // The Wk routes stack the road's filter (up to 8 poles) and Wk's 8 poles, 0.4 to
        // 100 Hz, on the model's: they agree to 4e-8 (the ISO road's two Wk routes to about
        // 1e-8), six orders under any filter's fit error.
        assert!(max_wk < 1e-7, "worst Wk relative difference {max_wk:e}");
    }

    /// Waviness 2 gives constant filters (no filter poles): the route is the ISO modal
    /// route to 1e-12, and the Wk-weighted BAcc by both shaped routes is the ISO road's
    /// ([`crate::criteria::bacc_wk`]) to 1e-12 (modal) and 1e-9 (Lyapunov).
    #[test]
    fn waviness_two_is_the_iso_modal_route() {
        let car = Car::datum();
        for tracks in [Tracks::Correlated, Tracks::Independent] {
            let road = Road {
                tracks,
                ..Road::default()
            };
            let shaped = ShapedRoad::iso(&road, 2.0).unwrap();
            for model in [quarter_car(&car.quarter()), full_car(&car)] {
                let a = criteria_shaped_modal(&model, &shaped).unwrap();
                let b = crate::criteria::criteria_modal(&model, &road).unwrap();
                assert!(worst(a, b) < 1e-12, "{a:?} vs {b:?}");
                let iso = crate::criteria::bacc_wk(&model, &road).unwrap();
                let modal = bacc_wk_shaped_modal(&model, &shaped).unwrap();
                let lyap = bacc_wk_shaped(&model, &shaped).unwrap();
                assert!((modal / iso - 1.0).abs() < 1e-12, "{modal} vs {iso}");
                assert!((lyap / iso - 1.0).abs() < 1e-9, "{lyap} vs {iso}");
            }
        }
    }

    /// A road warp is refused as by the Lyapunov route.
    #[test]
    fn a_road_warp_is_refused() {
        let mut car = Car::datum();
        car.track_rear = 1.4;
        let road = Road {
            tracks: Tracks::Independent,
            ..Road::default()
        };
        let shaped = ShapedRoad::iso(&road, 2.5).unwrap();
        let e = criteria_shaped_fast(&full_car(&car), &shaped).unwrap_err();
        assert!(matches!(e, RideError::RoadWarp(_)), "{e:?}");
    }
}
