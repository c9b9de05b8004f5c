//! A fitted surrogate held to what a model of the car can give.
//!
//! A surrogate is a fit, not physics: far outside the box it was fitted on, or with too
//! few samples for its box, it can predict an RMS that is negative, zero or not finite.
//! No such number may reach a map, a front, a pick or a file, so every fitted surrogate
//! is wrapped in [`Guarded`]: a prediction that is not a finite RMS > 0 is an error that
//! says where and why, and so is a design more than [`EXTRAPOLATION_LIMIT`] of the box's
//! width beyond the box the surrogate was fitted on. Maps, fronts and the page show the
//! message instead of the prediction; the fidelity study shows the surrogate's row as
//! skipped with it.

use super::record::ModelRecord;
use super::{FitDiagnostics, Parameter, Surrogate, SurrogateSpec};
use crate::car::QuarterCar;
use crate::design::DesignBox;
use crate::domain::num;
use crate::error::{Result, RideError};
use crate::evaluate::{Criteria, Evaluator};

/// How far beyond its fitted box a surrogate may be asked, as a share of the box's width
/// along each axis (0.1: 10 %). The page lets a design leave the box; the surrogate's
/// column then shows this refusal rather than an extrapolation.
const EXTRAPOLATION_LIMIT: f64 = 0.1;

/// A fitted surrogate whose predictions are checked (module docs): what
/// [`SurrogateSpec::fit`] returns.
pub struct Guarded {
    inner: ModelRecord,
    fitted: DesignBox,
}

impl Guarded {
    /// `inner`, fitted over `fitted`, with its predictions checked. A record adopted from
    /// another session ([`Guarded::record`]) is guarded again this way.
    pub(crate) fn new(inner: ModelRecord, fitted: DesignBox) -> Guarded {
        Guarded { inner, fitted }
    }

    /// The fitted model as data, to be rebuilt elsewhere with the same predictions;
    /// `None` on a measured road, whose LoFi route is not data.
    pub fn record(&self) -> Option<ModelRecord> {
        (!self.inner.model().on_measured_road()).then(|| self.inner.clone())
    }

    /// Refuses a design beyond [`EXTRAPOLATION_LIMIT`] of the fitted box.
    fn check_reach(&self, ks: f64, cs: f64) -> Result<()> {
        let (u, v) = self.fitted.normalize(ks, cs);
        let beyond = |t: f64| (-t).max(t - 1.0).max(0.0);
        let worst = beyond(u).max(beyond(v));
        if worst <= EXTRAPOLATION_LIMIT {
            return Ok(());
        }
        let b = &self.fitted;
        Err(RideError::field(
            "surrogate",
            format!(
                "{} was fitted over Ks {}..{} N/m, Cs {}..{} N s/m; Ks {} N/m, Cs {} N s/m lies {:.0} % of the box beyond it, further than the {:.0} % a fit can vouch for: move the design into the box or widen the box",
                self.inner.model().name(),
                num(b.ks_min),
                num(b.ks_max),
                num(b.cs_min),
                num(b.cs_max),
                num(ks),
                num(cs),
                100.0 * worst,
                100.0 * EXTRAPOLATION_LIMIT
            ),
        ))
    }
}

/// Refuses criteria that are not an RMS: each must be finite and > 0. `who` names the
/// evaluator in the message.
pub(crate) fn check_rms(who: &str, ks: f64, cs: f64, c: &Criteria) -> Result<()> {
    const NAMES: [(&str, &str); 3] = [("BAcc", "m/s^2"), ("DTL", "N"), ("SWS", "m")];
    for (value, (name, unit)) in c.to_array().into_iter().zip(NAMES) {
        if !(value.is_finite() && value > 0.0) {
            return Err(RideError::field(
                "surrogate",
                format!(
                    "{who} predicts an RMS {name} of {} {unit} at Ks {} N/m, Cs {} N s/m, which no car can have (an RMS is > 0): the fit does not hold over this design box; fit it on more samples (plan) or narrow the box",
                    num(value),
                    num(ks),
                    num(cs)
                ),
            ));
        }
    }
    Ok(())
}

impl Evaluator for Guarded {
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
        // The design's own faults first (they name ks or cs), then the fit's reach.
        if !crate::car::design_in_domain(ks, cs) {
            crate::car::check_design(ks, cs)?;
        }
        self.check_reach(ks, cs)?;
        let c = self.inner.model().evaluate(ks, cs)?;
        check_rms(&self.inner.model().name(), ks, cs, &c)?;
        Ok(c)
    }

    fn name(&self) -> String {
        self.inner.model().name()
    }
}

impl Surrogate for Guarded {
    fn spec(&self) -> SurrogateSpec {
        self.inner.model().spec()
    }

    fn tuning(&self) -> Vec<Parameter> {
        self.inner.model().tuning()
    }

    fn diagnostics(&self) -> Vec<FitDiagnostics> {
        self.inner.model().diagnostics()
    }

    fn tuned_quarters(&self, ks: f64, cs: f64) -> Result<Option<[QuarterCar; 3]>> {
        crate::car::check_design(ks, cs)?;
        self.check_reach(ks, cs)?;
        self.inner.model().tuned_quarters(ks, cs)
    }

    fn relative_std(&self, ks: f64, cs: f64) -> Result<Option<[f64; 3]>> {
        crate::car::check_design(ks, cs)?;
        self.check_reach(ks, cs)?;
        self.inner.model().relative_std(ks, cs)
    }

    fn on_measured_road(&self) -> bool {
        self.inner.model().on_measured_road()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surrogate::{sample_plan, LmOptions, PlanSpec, Setting};
    use crate::{Car, HiFi, Road};

    fn fitted(spec: &str, plan: &str) -> Guarded {
        let (car, road, b) = (Car::datum(), Road::default(), DesignBox::default());
        let hifi = HiFi::new(&car, &road).unwrap();
        let plan = PlanSpec::parse(plan).unwrap().plan().unwrap();
        let samples = sample_plan(&hifi, &plan, &b).unwrap();
        let setting = Setting::new(&car, &road, &b).unwrap();
        SurrogateSpec::parse(spec)
            .unwrap()
            .fit(&setting, &samples, &LmOptions::default())
            .unwrap()
    }

    #[test]
    fn inside_the_box_the_prediction_passes_unchanged_and_far_outside_it_is_refused() {
        let s = fitted("rba-mul-rbf-mq", "ae:10");
        let c = s.evaluate(19_960.0, 1_290.0).unwrap();
        // The datum's HiFi BAcc is 0.479251 m/s^2 (README); the surrogate within 1 %.
        assert!((c.bacc / 0.479_251 - 1.0).abs() < 0.01, "{c:?}");
        // 7 % beyond the Ks bound (40 kN/m + 2 kN/m) is allowed, 20 % is not.
        assert!(s.evaluate(42_000.0, 1_290.0).is_ok());
        let e = s.evaluate(46_000.0, 1_290.0).unwrap_err().to_string();
        assert!(
            e.starts_with("surrogate: rba-mul-rbf-mq was fitted over Ks 10000..40000 N/m")
                && e.contains("lies 20 % of the box beyond it"),
            "{e}"
        );
        assert!(s.tuned_quarters(10_000.0, 100.0).is_err());
    }

    #[test]
    fn an_impossible_rms_is_refused_naming_the_criterion() {
        let c = Criteria {
            bacc: -0.12,
            dtl: 300.0,
            sws: 0.005,
        };
        let e = check_rms("data-quad", 1e4, 500.0, &c)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("surrogate: data-quad predicts an RMS BAcc of -0.12 m/s^2 at Ks 10000 N/m, Cs 500 N s/m"),
            "{e}"
        );
        let nan = Criteria { sws: f64::NAN, ..c };
        let nan = Criteria { bacc: 0.4, ..nan };
        assert!(check_rms("x", 1e4, 500.0, &nan)
            .unwrap_err()
            .to_string()
            .contains("SWS of NaN m"));
    }
}
