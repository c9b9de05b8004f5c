//! Design objective space (DOS): the design objectives that make a point of the
//! design criteria space feasible, and which objective each infeasible point breaks.

use crate::car::{bounce_frequency, damping_ratio, Car};
use crate::error::{Result, RideError};
use crate::evaluate::{Criteria, Evaluator};
use serde::{Deserialize, Serialize};

/// Editable design objectives (METHOD.md section 3). `None` switches an objective off.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct DesignObjectives {
    /// Upper limit on RMS suspension working space, m (default 0.007 m, on).
    pub sws_limit: Option<f64>,
    /// Allowed body-bounce frequency band `(lo, hi)`, Hz (literature: 0.8..1.5 Hz; off by default).
    pub bounce_band: Option<(f64, f64)>,
    /// Allowed body damping-ratio band `(lo, hi)`, - (literature: 0.2..0.5; off by default).
    pub damping_band: Option<(f64, f64)>,
    /// "No worse than the datum car" for `[bacc, dtl, sws]`.
    pub no_worse_than_datum: [bool; 3],
    /// Tyre-load margin `k` (0 < k <= 100): `sigma_DTL <= F_static / k` (off by default).
    /// With a Gaussian tyre load, k = 3 keeps the wheel on the road (DTL > F_static is the
    /// tyre leaving it) all but 0.135 % of the time; smooth roads need larger k to bind.
    #[serde(default)]
    pub dtl_margin: Option<f64>,
    /// Travel budget `(available bump travel m, sigma factor n)`: `n sigma_SWS <= travel`
    /// (off by default; for example 3 sigma within 25 mm).
    #[serde(default)]
    pub travel: Option<(f64, f64)>,
}

impl Default for DesignObjectives {
    fn default() -> Self {
        DesignObjectives {
            sws_limit: Some(0.007),
            bounce_band: None,
            damping_band: None,
            no_worse_than_datum: [false; 3],
            dtl_margin: None,
            travel: None,
        }
    }
}

/// What the objectives need to know about the car besides the criteria.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DosContext {
    /// Quarter-car sprung mass `ms = M b / (2 L)`, kg.
    pub sprung_mass: f64,
    /// Front tyre vertical stiffness, N/m.
    pub tire_stiffness: f64,
    /// The datum car's criteria (for "no worse than datum").
    pub datum: Criteria,
    /// Static front wheel load `F_static`, N (for the tyre-load margin).
    pub static_wheel_load: f64,
}

impl DosContext {
    /// The context of `car` (its quarter car's sprung mass and front tyre rate) with
    /// the datum's criteria `datum`.
    pub fn new(car: &Car, datum: Criteria) -> DosContext {
        let q = car.quarter();
        DosContext {
            sprung_mass: q.ms,
            tire_stiffness: q.kt,
            datum,
            static_wheel_load: car.front_wheel_load(),
        }
    }

    /// The context of `car` with the datum's criteria by `model` at the car's own front
    /// spring and damper (each map and front compares a model with its own datum).
    pub fn of_model<E: Evaluator + ?Sized>(car: &Car, model: &E) -> Result<DosContext> {
        Ok(DosContext::new(
            car,
            model.evaluate(car.front.spring, car.front.damper)?,
        ))
    }
}

/// One design objective, as named in messages and on the overlay.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Objective {
    /// RMS SWS above its limit.
    SwsLimit,
    /// Body-bounce frequency outside its band.
    BounceBand,
    /// Body damping ratio outside its band.
    DampingBand,
    /// BAcc worse than the datum car.
    BaccDatum,
    /// DTL worse than the datum car.
    DtlDatum,
    /// SWS worse than the datum car.
    SwsDatum,
    /// RMS DTL above the static wheel load over the margin.
    DtlMargin,
    /// The sigma multiple of RMS SWS beyond the travel budget.
    Travel,
}

impl Objective {
    /// What the objective bounds: `"limit"`, a limit on a response (SWS, tyre load,
    /// travel); `"band"`, a band on a ride property of the design (bounce frequency,
    /// damping ratio); `"datum"`, a criterion no worse than the datum car's. The page
    /// hatches each family in its own pattern.
    pub fn family(self) -> &'static str {
        match self {
            Objective::SwsLimit | Objective::DtlMargin | Objective::Travel => "limit",
            Objective::BounceBand | Objective::DampingBand => "band",
            Objective::BaccDatum | Objective::DtlDatum | Objective::SwsDatum => "datum",
        }
    }

    /// A short human-readable label.
    pub fn label(self) -> &'static str {
        match self {
            Objective::SwsLimit => "SWS limit",
            Objective::BounceBand => "body-bounce frequency band",
            Objective::DampingBand => "damping-ratio band",
            Objective::BaccDatum => "BAcc no worse than datum",
            Objective::DtlDatum => "DTL no worse than datum",
            Objective::SwsDatum => "SWS no worse than datum",
            Objective::DtlMargin => "tyre-load margin",
            Objective::Travel => "travel budget",
        }
    }
}

impl DesignObjectives {
    /// Checks every limit and band against its physical range ([`crate::domain`]) and
    /// that bands are ordered; errors name the objective's field.
    pub fn validate(&self) -> Result<()> {
        use crate::domain::{
            BOUNCE_BAND, DAMPING_BAND, DTL_MARGIN, SWS_LIMIT, TRAVEL, TRAVEL_SIGMAS,
        };
        if let Some(l) = self.sws_limit {
            if !(l.is_finite() && l > 0.0) {
                return Err(RideError::field(
                    "sws_limit",
                    "must be a finite number > 0 (m)",
                ));
            }
            SWS_LIMIT.check("sws_limit", l)?;
        }
        for (name, band, limit) in [
            ("bounce_band", self.bounce_band, &BOUNCE_BAND),
            ("damping_band", self.damping_band, &DAMPING_BAND),
        ] {
            if let Some((lo, hi)) = band {
                if !(lo.is_finite() && hi.is_finite() && lo >= 0.0 && lo < hi) {
                    return Err(RideError::field(name, "needs finite 0 <= lo < hi"));
                }
                limit.check(name, lo)?;
                limit.check(name, hi)?;
            }
        }
        if let Some(k) = self.dtl_margin {
            DTL_MARGIN.check("dtl_margin", k)?;
        }
        if let Some((travel, n)) = self.travel {
            TRAVEL.check("travel", travel)?;
            TRAVEL_SIGMAS.check("travel", n)?;
        }
        Ok(())
    }

    /// Signed constraint values `g <= 0` when met, one per active objective, in a
    /// fixed order; normalised so that 0.01 means "1 % beyond the bound".
    pub(crate) fn constraints(
        &self,
        ctx: &DosContext,
        ks: f64,
        cs: f64,
        c: &Criteria,
    ) -> Vec<(Objective, f64)> {
        let mut g = Vec::with_capacity(6);
        self.each_constraint(ctx, ks, cs, c, |o, v| g.push((o, v)));
        g
    }

    /// Calls `f(objective, g)` for each active objective in the order of
    /// [`Self::constraints`], without allocating (the maps judge every cell with it).
    pub(crate) fn each_constraint(
        &self,
        ctx: &DosContext,
        ks: f64,
        cs: f64,
        c: &Criteria,
        mut f: impl FnMut(Objective, f64),
    ) {
        if let Some(l) = self.sws_limit {
            f(Objective::SwsLimit, c.sws / l - 1.0);
        }
        if let Some((lo, hi)) = self.bounce_band {
            let fb = bounce_frequency(ks, ctx.tire_stiffness, ctx.sprung_mass);
            f(Objective::BounceBand, band_violation(fb, lo, hi));
        }
        if let Some((lo, hi)) = self.damping_band {
            let z = damping_ratio(ks, cs, ctx.sprung_mass);
            f(Objective::DampingBand, band_violation(z, lo, hi));
        }
        let objs = [
            Objective::BaccDatum,
            Objective::DtlDatum,
            Objective::SwsDatum,
        ];
        let (v, d) = (c.to_array(), ctx.datum.to_array());
        for i in 0..3 {
            if self.no_worse_than_datum[i] {
                f(objs[i], v[i] / d[i] - 1.0);
            }
        }
        if let Some(k) = self.dtl_margin {
            f(
                Objective::DtlMargin,
                k * c.dtl / ctx.static_wheel_load - 1.0,
            );
        }
        if let Some((travel, n)) = self.travel {
            f(Objective::Travel, n * c.sws / travel - 1.0);
        }
    }

    /// The objectives a design breaks (empty when feasible).
    pub fn broken(&self, ctx: &DosContext, ks: f64, cs: f64, c: &Criteria) -> Vec<Objective> {
        self.constraints(ctx, ks, cs, c)
            .into_iter()
            .filter(|(_, g)| *g > 0.0)
            .map(|(o, _)| o)
            .collect()
    }

    /// Total constraint violation `sum max(0, g)` (Deb's constraint domination uses it).
    pub fn violation(&self, ctx: &DosContext, ks: f64, cs: f64, c: &Criteria) -> f64 {
        self.constraints(ctx, ks, cs, c)
            .iter()
            .map(|(_, g)| g.max(0.0))
            .sum()
    }
}

/// Relative distance outside `[lo, hi]`: negative inside, positive outside.
fn band_violation(x: f64, lo: f64, hi: f64) -> f64 {
    ((lo - x) / lo.max(f64::MIN_POSITIVE)).max((x - hi) / hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ctx() -> DosContext {
        DosContext {
            sprung_mass: 467.7,
            tire_stiffness: 175_500.0,
            datum: Criteria {
                bacc: 1.0,
                dtl: 500.0,
                sws: 0.006,
            },
            static_wheel_load: 4_500.0,
        }
    }

    #[test]
    fn bounce_frequency_matches_hand_value() {
        // Kw = 20000*175500/195500 = 17953.96 N/m; sqrt(Kw/467.7)/(2 pi) = 0.98610 Hz
        let f = bounce_frequency(20_000.0, 175_500.0, 467.7);
        assert!((f - 0.986_10).abs() < 1e-4, "{f}");
    }

    #[test]
    fn broken_names_each_objective() {
        let o = DesignObjectives {
            bounce_band: Some((0.8, 1.5)),
            no_worse_than_datum: [true, false, false],
            ..Default::default()
        };
        let c = Criteria {
            bacc: 1.1,
            dtl: 400.0,
            sws: 0.008,
        };
        let b = o.broken(&ctx(), 20_000.0, 1500.0, &c);
        assert_eq!(b, vec![Objective::SwsLimit, Objective::BaccDatum]);
        let ok = Criteria {
            bacc: 0.9,
            dtl: 400.0,
            sws: 0.005,
        };
        assert!(o.broken(&ctx(), 20_000.0, 1500.0, &ok).is_empty());
        assert_eq!(o.violation(&ctx(), 20_000.0, 1500.0, &ok), 0.0);
    }

    /// The tyre-load margin and the travel budget by hand: with F_static = 4500 N and
    /// k = 3 the limit is 1500 N; 3 sigma of 9 mm SWS is 27 mm against a 25 mm budget.
    #[test]
    fn tyre_load_margin_and_travel_budget_by_hand() {
        let o = DesignObjectives {
            sws_limit: None,
            dtl_margin: Some(3.0),
            travel: Some((0.025, 3.0)),
            ..Default::default()
        };
        let c = |dtl: f64, sws: f64| Criteria {
            bacc: 1.0,
            dtl,
            sws,
        };
        let g = o.constraints(&ctx(), 20_000.0, 1500.0, &c(1600.0, 0.009));
        assert_eq!(g.len(), 2);
        assert_eq!(g[0].0, Objective::DtlMargin);
        assert!((g[0].1 - (3.0 * 1600.0 / 4500.0 - 1.0)).abs() < 1e-15);
        assert_eq!(g[1].0, Objective::Travel);
        assert!((g[1].1 - (27.0 / 25.0 - 1.0)).abs() < 1e-12);
        // Just inside both: 1499 N and 8.3 mm (24.9 mm at 3 sigma).
        assert!(o
            .broken(&ctx(), 20_000.0, 1500.0, &c(1499.0, 0.0083))
            .is_empty());
        assert_eq!(
            o.broken(&ctx(), 20_000.0, 1500.0, &c(1501.0, 0.0083)),
            vec![Objective::DtlMargin]
        );
        assert_eq!(
            o.broken(&ctx(), 20_000.0, 1500.0, &c(1499.0, 0.0084)),
            vec![Objective::Travel]
        );
    }

    #[test]
    fn bad_margin_and_travel_name_the_field() {
        for (o, field) in [
            (
                DesignObjectives {
                    dtl_margin: Some(0.0),
                    ..Default::default()
                },
                "dtl_margin",
            ),
            (
                DesignObjectives {
                    dtl_margin: Some(f64::NAN),
                    ..Default::default()
                },
                "dtl_margin",
            ),
            (
                DesignObjectives {
                    travel: Some((-0.02, 3.0)),
                    ..Default::default()
                },
                "travel",
            ),
            (
                DesignObjectives {
                    travel: Some((0.025, 0.0)),
                    ..Default::default()
                },
                "travel",
            ),
        ] {
            let e = o.validate().unwrap_err().to_string();
            assert!(e.starts_with(field), "{e}");
        }
    }

    #[test]
    fn bad_limits_name_the_field() {
        let o = DesignObjectives {
            sws_limit: Some(-1.0),
            ..Default::default()
        };
        assert!(o
            .validate()
            .unwrap_err()
            .to_string()
            .starts_with("sws_limit"));
    }
}
