//! The comfort objective (issue #16): unweighted RMS body acceleration (the thesis's
//! BAcc, the default) or the ISO 2631-1 Wk-weighted RMS body acceleration, both m/s^2 at
//! the body above the front wheel.
//!
//! [`WkComfort`] wraps any evaluator of the LoFi or the HiFi and puts the exact
//! Wk-weighted value ([`crate::criteria::bacc_wk`]: the modal route on the model with the
//! Wk filter's partial fractions, the Kronecker route behind it) in the comfort slot
//! [`Criteria::bacc`], so that every map, design objective ("BAcc no worse than the
//! datum" then compares Wk with the datum's Wk), front and pick uses it unchanged.

use crate::analysis::{HiFi, LoFi, ModelKind};
use crate::car::Car;
use crate::criteria::bacc_wk;
use crate::error::{parse_choice, Result, RideError};
use crate::evaluate::{Criteria, Evaluator};
use crate::model::{quarter_car, LinearModel};
use crate::road::Road;
use serde::{Deserialize, Serialize};
use strum::{EnumIter, EnumProperty, IntoStaticStr, VariantNames};

/// Which measure fills the comfort slot of the criteria.
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    Default,
    Serialize,
    Deserialize,
    EnumIter,
    EnumProperty,
    IntoStaticStr,
    VariantNames,
)]
#[serde(rename_all = "lowercase")]
#[strum(serialize_all = "lowercase")]
#[strum()]
pub enum Comfort {
    /// Unweighted RMS body acceleration, m/s^2 (the thesis's BAcc).
    #[default]
    Bacc,
    /// ISO 2631-1:1997 Wk-weighted RMS body acceleration, m/s^2.
    Wk,
}

impl std::str::FromStr for Comfort {
    type Err = RideError;
    fn from_str(s: &str) -> Result<Comfort> {
        Comfort::parse(s)
    }
}

impl Comfort {
    /// Parses "bacc" or "wk" (any case); errors name `comfort`.
    pub fn parse(s: &str) -> Result<Comfort> {
        parse_choice("comfort", s)
    }

    /// Whether this is the default, unweighted BAcc (reports leave the field out then, so
    /// their output is what it was before the option existed).
    pub(crate) fn is_bacc(&self) -> bool {
        *self == Comfort::Bacc
    }

    /// The short label of the comfort axis or column: `BAcc` or `BAcc (Wk)`.
    pub fn label(&self) -> &'static str {
        match self {
            Comfort::Bacc => "BAcc",
            Comfort::Wk => "BAcc (Wk)",
        }
    }

    /// The long name of the measure.
    pub(crate) fn long_name(&self) -> &'static str {
        match self {
            Comfort::Bacc => "RMS body acceleration",
            Comfort::Wk => "ISO 2631-1 Wk-weighted RMS body acceleration",
        }
    }

    /// The LoFi (`quarter`) or HiFi (`full`) evaluator of `car` on `road` with this
    /// comfort measure.
    pub fn evaluator(
        &self,
        model: ModelKind,
        car: &Car,
        road: &Road,
    ) -> Result<Box<dyn Evaluator + Sync>> {
        Ok(match (self, model) {
            (Comfort::Bacc, ModelKind::Quarter) => Box::new(LoFi::new(car, road)),
            (Comfort::Bacc, ModelKind::Full) => Box::new(HiFi::new(car, road)?),
            (Comfort::Wk, ModelKind::Quarter) => Box::new(WkComfort::quarter(car, road)),
            (Comfort::Wk, ModelKind::Full) => Box::new(WkComfort::full(HiFi::new(car, road)?)),
        })
    }
}

/// The model whose Wk-weighted body acceleration fills the comfort slot.
#[derive(Debug, Clone, PartialEq)]
enum Source {
    /// The LoFi: the front quarter car.
    Quarter(LoFi),
    /// The HiFi (its own criteria give DTL and SWS).
    Full(Box<HiFi>),
}

/// The LoFi or HiFi evaluator with the Wk-weighted RMS body acceleration (m/s^2) in
/// [`Criteria::bacc`]; DTL and SWS are the evaluator's own, bit for bit.
#[derive(Debug, Clone, PartialEq)]
pub struct WkComfort {
    source: Source,
}

impl WkComfort {
    /// The LoFi of `car` on `road` with Wk comfort.
    pub fn quarter(car: &Car, road: &Road) -> WkComfort {
        WkComfort {
            source: Source::Quarter(LoFi::new(car, road)),
        }
    }

    /// The HiFi `hifi` with Wk comfort.
    pub fn full(hifi: HiFi) -> WkComfort {
        WkComfort {
            source: Source::Full(Box::new(hifi)),
        }
    }

    /// The linear model at design `(ks, cs)` and its road.
    fn model_at(&self, ks: f64, cs: f64) -> (LinearModel, &Road) {
        match &self.source {
            Source::Quarter(lofi) => {
                let mut q = lofi.car.quarter();
                q.ks = ks;
                q.cs = cs;
                (quarter_car(&q), &lofi.road)
            }
            Source::Full(hifi) => (hifi.model_at(ks, cs), hifi.road()),
        }
    }

    /// The Wk-weighted RMS body acceleration at `(ks, cs)`, m/s^2.
    pub fn bacc_wk(&self, ks: f64, cs: f64) -> Result<f64> {
        let (model, road) = self.model_at(ks, cs);
        bacc_wk(&model, road)
    }
}

impl Evaluator for WkComfort {
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
        // The evaluator checks the design (and names a bad one) before the model is built.
        let plain = match &self.source {
            Source::Quarter(lofi) => lofi.evaluate(ks, cs)?,
            Source::Full(hifi) => hifi.evaluate(ks, cs)?,
        };
        Ok(Criteria {
            bacc: self.bacc_wk(ks, cs)?,
            ..plain
        })
    }
    fn name(&self) -> String {
        match &self.source {
            Source::Quarter(lofi) => lofi.name(),
            Source::Full(hifi) => hifi.name(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::criteria::{bacc_wk_exact, bacc_wk_spectral};
    use crate::road::Tracks;

    #[test]
    fn parse_names_the_option() {
        assert_eq!("bacc".parse::<Comfort>().unwrap(), Comfort::Bacc);
        assert_eq!(" WK ".parse::<Comfort>().unwrap(), Comfort::Wk);
        let e = "foo".parse::<Comfort>().unwrap_err().to_string();
        assert_eq!(e, "comfort: 'foo' is not 'bacc' or 'wk'");
        assert_eq!(Comfort::default(), Comfort::Bacc);
    }

    /// The comfort slot is the frequency route's Wk value of the design to 1e-8 (and the
    /// Kronecker route's); DTL and SWS are the plain evaluator's, bit for bit.
    #[test]
    fn wk_slot_equals_the_frequency_route() {
        let car = Car::datum();
        for tracks in [Tracks::Correlated, Tracks::Independent] {
            let road = Road {
                tracks,
                ..Road::default()
            };
            for model in [ModelKind::Quarter, ModelKind::Full] {
                let wk = Comfort::Wk.evaluator(model, &car, &road).unwrap();
                let plain = Comfort::Bacc.evaluator(model, &car, &road).unwrap();
                for (ks, cs) in [(12_000.0, 800.0), (25_000.0, 2500.0), (38_000.0, 3900.0)] {
                    let c = wk.evaluate(ks, cs).unwrap();
                    let p = plain.evaluate(ks, cs).unwrap();
                    assert_eq!((c.dtl, c.sws), (p.dtl, p.sws));
                    let m = model.build(&car.with_front(ks, cs).unwrap());
                    let spectral = bacc_wk_spectral(&m, &road, 1e-11).unwrap();
                    let exact = bacc_wk_exact(&m, &road).unwrap();
                    assert!(
                        (c.bacc / spectral - 1.0).abs() < 1e-8,
                        "{model:?} {ks} {cs}"
                    );
                    assert!((c.bacc / exact - 1.0).abs() < 1e-8, "{model:?} {ks} {cs}");
                }
            }
        }
    }

    /// A bad design is named as the plain evaluator names it.
    #[test]
    fn bad_design_is_named() {
        let wk = Comfort::Wk
            .evaluator(ModelKind::Full, &Car::datum(), &Road::default())
            .unwrap();
        let e = wk.evaluate(20_000.0, 0.0).unwrap_err().to_string();
        assert!(e.starts_with("cs: ") || e.contains("cs"), "{e}");
    }

    /// Cost per design of the Wk slot (the modal route) against the Kronecker route, on
    /// the LoFi and the HiFi: `cargo test --release --lib comfort::tests::cost -- --ignored --nocapture`.
    #[test]
    #[ignore]
    fn cost() {
        let car = Car::datum();
        let road = Road::default();
        let median = |mut v: Vec<f64>| {
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        };
        for model in [ModelKind::Quarter, ModelKind::Full] {
            let wk = Comfort::Wk.evaluator(model, &car, &road).unwrap();
            let plain = Comfort::Bacc.evaluator(model, &car, &road).unwrap();
            let time = |f: &dyn Fn(f64, f64)| {
                median(
                    (0..41)
                        .map(|i| {
                            let (ks, cs) = (10_000.0 + 750.0 * i as f64, 500.0 + 87.5 * i as f64);
                            let t = std::time::Instant::now();
                            for _ in 0..5 {
                                f(ks, cs);
                            }
                            t.elapsed().as_secs_f64() / 5.0
                        })
                        .collect(),
                )
            };
            let t_wk = time(&|ks, cs| {
                wk.evaluate(ks, cs).unwrap();
            });
            let t_plain = time(&|ks, cs| {
                plain.evaluate(ks, cs).unwrap();
            });
            let t_kron = time(&|ks, cs| {
                let m = model.build(&car.with_front(ks, cs).unwrap());
                bacc_wk_exact(&m, &road).unwrap();
            });
            println!(
                "{model:?}: per design, median over 41 designs: plain {:.1} us, with Wk (modal) {:.1} us, Kronecker Wk alone {:.1} us",
                1e6 * t_plain,
                1e6 * t_wk,
                1e6 * t_kron
            );
        }
    }
}
