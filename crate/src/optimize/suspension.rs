//! The suspension design problem: minimise `[BAcc (m/s^2), DTL (N)]` over
//! `x = [Ks (N/m), Cs (N s/m)]` in the design box, subject to the design objectives,
//! on any [`Evaluator`] (LoFi, HiFi or a surrogate), counting its evaluations.

use super::problem::{Eval, Problem, Solution};
use crate::car::{bounce_frequency, damping_ratio};
use crate::design::DesignBox;
use crate::dos::{DesignObjectives, DosContext, Objective};
use crate::error::{Result, RideError};
use crate::evaluate::{Criteria, Evaluator};
use serde::Serialize;
use std::cell::{Cell, RefCell};

/// An evaluator that counts its calls (how many model runs a study cost).
pub(crate) struct Counted<E> {
    inner: E,
    count: Cell<usize>,
}

impl<E: Evaluator> Counted<E> {
    /// Wraps `inner` with the count at 0.
    pub(crate) fn new(inner: E) -> Self {
        Counted {
            inner,
            count: Cell::new(0),
        }
    }

    /// Wraps `inner` with the count at `made`: runs made before it (a kept fit's samples,
    /// which a report counts with its validation grid's).
    pub(crate) fn with_count(inner: E, made: usize) -> Self {
        Counted {
            inner,
            count: Cell::new(made),
        }
    }

    /// Calls made so far, failed ones included.
    pub(crate) fn count(&self) -> usize {
        self.count.get()
    }
}

impl<E: Evaluator> Evaluator for Counted<E> {
    /// The inner evaluation, counted; past [`crate::budget::HARD_RUNS`] calls an error
    /// naming `grid` (the optimisers' runs are bounded, whatever their estimate said).
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
        let n = self.count.get() + 1;
        self.count.set(n);
        if n as u64 > crate::budget::HARD_RUNS {
            return Err(RideError::field(
                "grid",
                format!(
                    "the optimiser has made {} model runs, the most one command may (lower --grid, --levels or --generations)",
                    crate::budget::group(crate::budget::HARD_RUNS)
                ),
            ));
        }
        self.inner.evaluate(ks, cs)
    }
    fn name(&self) -> String {
        self.inner.name()
    }
}

/// One point of a suspension front, with all three criteria.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FrontPoint {
    /// Front spring rate, N/m.
    pub ks: f64,
    /// Front damper rate, N s/m.
    pub cs: f64,
    /// RMS body acceleration, m/s^2.
    pub bacc: f64,
    /// RMS dynamic tyre load, N.
    pub dtl: f64,
    /// RMS suspension working space, m.
    pub sws: f64,
}

impl FrontPoint {
    /// Converts an optimiser's solutions (`x = [ks, cs]`) into front points.
    pub(crate) fn from_solutions(front: &[Solution<Criteria>]) -> Vec<FrontPoint> {
        front
            .iter()
            .map(|s| FrontPoint {
                ks: s.x[0],
                cs: s.x[1],
                bacc: s.eval.info.bacc,
                dtl: s.eval.info.dtl,
                sws: s.eval.info.sws,
            })
            .collect()
    }

    /// The criteria of the point.
    pub(crate) fn criteria(&self) -> Criteria {
        Criteria {
            bacc: self.bacc,
            dtl: self.dtl,
            sws: self.sws,
        }
    }
}

/// For one design objective, the evaluated design that came closest to meeting it.
#[derive(Debug, Clone, Copy)]
struct Closest {
    objective: Objective,
    g: f64,
    ks: f64,
    cs: f64,
    criteria: Criteria,
}

/// The design evaluated so far with the least total violation, and what it breaks
/// (the single-case problem's and the robust problem's explanation of an empty feasible set).
#[derive(Debug, Clone)]
pub(crate) struct LeastViolation {
    pub(crate) violation: f64,
    pub(crate) ks: f64,
    pub(crate) cs: f64,
    pub(crate) broken: Vec<Objective>,
}

impl LeastViolation {
    /// Keeps design `(ks, cs)` in `least` when its total `violation` is smaller than the
    /// kept one's; `g` are its constraint values (`> 0`: broken).
    pub(crate) fn keep(
        least: &RefCell<Option<Self>>,
        ks: f64,
        cs: f64,
        g: &[(Objective, f64)],
        violation: f64,
    ) {
        let mut least = least.borrow_mut();
        if least.as_ref().is_none_or(|l| violation < l.violation) {
            let broken = g
                .iter()
                .filter(|(_, gj)| *gj > 0.0)
                .map(|(o, _)| *o)
                .collect();
            *least = Some(LeastViolation {
                violation,
                ks,
                cs,
                broken,
            });
        }
    }
}

/// Bi-objective suspension problem on an evaluator `E`; remembers, per design
/// objective, how close the evaluated designs came, to explain an empty feasible set.
pub struct SuspensionProblem<E> {
    evaluator: Counted<E>,
    design: DesignBox,
    objectives: DesignObjectives,
    ctx: DosContext,
    closest: RefCell<Vec<Closest>>,
    least: RefCell<Option<LeastViolation>>,
}

impl<E: Evaluator> SuspensionProblem<E> {
    /// Checks the box and the objectives and sets up the problem.
    pub fn new(
        evaluator: E,
        design: DesignBox,
        objectives: DesignObjectives,
        ctx: DosContext,
    ) -> Result<Self> {
        design.validate()?;
        design.check_on(&crate::car::DesignDomain::new(
            ctx.sprung_mass,
            ctx.tire_stiffness,
        ))?;
        objectives.validate()?;
        Ok(SuspensionProblem {
            evaluator: Counted::new(evaluator),
            design,
            objectives,
            ctx,
            closest: RefCell::new(Vec::new()),
            least: RefCell::new(None),
        })
    }

    /// Evaluator calls made so far.
    pub(crate) fn evaluations(&self) -> usize {
        self.evaluator.count()
    }

    /// The evaluator's name.
    pub(crate) fn evaluator_name(&self) -> String {
        self.evaluator.name()
    }

    /// The car context (sprung mass, tyre rate, datum criteria).
    pub(crate) fn context(&self) -> &DosContext {
        &self.ctx
    }

    /// Keeps, per objective, the design with the smallest constraint value `g`, and the
    /// design with the least total violation.
    fn remember(&self, ks: f64, cs: f64, c: &Criteria, g: &[(Objective, f64)], violation: f64) {
        let mut closest = self.closest.borrow_mut();
        for &(objective, gj) in g {
            let entry = Closest {
                objective,
                g: gj,
                ks,
                cs,
                criteria: *c,
            };
            match closest.iter_mut().find(|e| e.objective == objective) {
                Some(e) if gj < e.g => *e = entry,
                Some(_) => {}
                None => closest.push(entry),
            }
        }
        LeastViolation::keep(&self.least, ks, cs, g, violation);
    }

    /// Why `c` at the closest design still breaks its objective, in words.
    fn describe(&self, e: &Closest) -> String {
        let (ks, cs, c, d) = (e.ks, e.cs, e.criteria, self.ctx.datum);
        let at = format!("at Ks = {ks:.0} N/m, Cs = {cs:.0} N s/m");
        match e.objective {
            Objective::SwsLimit => format!(
                "SWS limit {:.1} mm is exceeded everywhere in the design box (smallest SWS {:.1} mm {at})",
                self.objectives.sws_limit.unwrap_or(f64::NAN) * 1e3,
                c.sws * 1e3
            ),
            Objective::BounceBand => {
                let (lo, hi) = self.objectives.bounce_band.unwrap_or((f64::NAN, f64::NAN));
                let f = bounce_frequency(ks, self.ctx.tire_stiffness, self.ctx.sprung_mass);
                format!(
                    "body-bounce frequency band {lo:.2}..{hi:.2} Hz is missed everywhere in the design box (closest {f:.2} Hz {at})"
                )
            }
            Objective::DampingBand => {
                let (lo, hi) = self.objectives.damping_band.unwrap_or((f64::NAN, f64::NAN));
                let z = damping_ratio(ks, cs, self.ctx.sprung_mass);
                format!(
                    "damping-ratio band {lo:.2}..{hi:.2} is missed everywhere in the design box (closest {z:.3} {at})"
                )
            }
            Objective::BaccDatum => format!(
                "BAcc no worse than datum ({:.3} m/s^2) is broken everywhere in the design box (smallest BAcc {:.3} m/s^2 {at})",
                d.bacc, c.bacc
            ),
            Objective::DtlDatum => format!(
                "DTL no worse than datum ({:.1} N) is broken everywhere in the design box (smallest DTL {:.1} N {at})",
                d.dtl, c.dtl
            ),
            Objective::SwsDatum => format!(
                "SWS no worse than datum ({:.2} mm) is broken everywhere in the design box (smallest SWS {:.2} mm {at})",
                d.sws * 1e3,
                c.sws * 1e3
            ),
            Objective::DtlMargin => {
                let k = self.objectives.dtl_margin.unwrap_or(f64::NAN);
                format!(
                    "tyre-load margin (RMS DTL at most F_static / {k} = {:.1} N) is broken everywhere in the design box (smallest DTL {:.1} N {at})",
                    self.ctx.static_wheel_load / k,
                    c.dtl
                )
            }
            Objective::Travel => {
                let (travel, n) = self.objectives.travel.unwrap_or((f64::NAN, f64::NAN));
                format!(
                    "travel budget ({n} x RMS SWS within {:.1} mm) is exceeded everywhere in the design box (smallest {n} x SWS {:.1} mm {at})",
                    travel * 1e3,
                    n * c.sws * 1e3
                )
            }
        }
    }
}

/// The [`DesignObjectives`] field that switches an objective on.
fn field_of(objective: Objective) -> &'static str {
    match objective {
        Objective::SwsLimit => "sws_limit",
        Objective::BounceBand => "bounce_band",
        Objective::DampingBand => "damping_band",
        Objective::BaccDatum | Objective::DtlDatum | Objective::SwsDatum => "no_worse_than_datum",
        Objective::DtlMargin => "dtl_margin",
        Objective::Travel => "travel",
    }
}

impl<E: Evaluator> Problem for SuspensionProblem<E> {
    type Info = Criteria;

    /// `[(ks_min, ks_max), (cs_min, cs_max)]`, N/m and N s/m.
    fn bounds(&self) -> Vec<(f64, f64)> {
        let b = &self.design;
        vec![(b.ks_min, b.ks_max), (b.cs_min, b.cs_max)]
    }

    /// `f = [BAcc, DTL]`, violation `sum max(0, g_j)` over the active objectives.
    fn evaluate(&self, x: &[f64]) -> Result<Eval<Criteria>> {
        let (ks, cs) = (x[0], x[1]);
        let c = self.evaluator.evaluate(ks, cs)?;
        if !c.to_array().iter().all(|v| v.is_finite()) {
            return Err(RideError::Numerical(format!(
                "{} gave non-finite criteria at Ks = {ks} N/m, Cs = {cs} N s/m",
                self.evaluator.name()
            )));
        }
        let g = self.objectives.constraints(&self.ctx, ks, cs, &c);
        let violation = g.iter().map(|(_, gj)| gj.max(0.0)).sum();
        self.remember(ks, cs, &c, &g, violation);
        Ok(Eval {
            f: [c.bacc, c.dtl],
            violation,
            info: c,
        })
    }

    /// Names every objective that all evaluated designs break (the most broken first),
    /// with the closest any design came; when each objective is met somewhere but never
    /// all together, names them and what the least-violating design breaks. The error's
    /// field is the binding objective's [`DesignObjectives`] field.
    fn infeasible(&self) -> RideError {
        let mut everywhere: Vec<Closest> = self
            .closest
            .borrow()
            .iter()
            .copied()
            .filter(|e| e.g > 0.0)
            .collect();
        // Descending g: the negated key's ascending order (crate::order).
        crate::order::sort_by_f64_key(&mut everywhere, |e| -e.g);
        if let Some(first) = everywhere.first() {
            let reasons: Vec<String> = everywhere.iter().map(|e| self.describe(e)).collect();
            return RideError::Infeasible {
                field: field_of(first.objective).into(),
                reason: format!("no feasible design: {}", reasons.join("; ")),
            };
        }
        match self.least.borrow().as_ref() {
            Some(l) => {
                let all: Vec<&str> = self
                    .closest
                    .borrow()
                    .iter()
                    .map(|e| e.objective.label())
                    .collect();
                let broken: Vec<&str> = l.broken.iter().map(|o| o.label()).collect();
                RideError::Infeasible {
                    field: l.broken.first().map_or("objectives", |&o| field_of(o)).into(),
                    reason: format!(
                        "no feasible design: {} are each met somewhere in the design box but never together; \
                         the closest design (Ks = {:.0} N/m, Cs = {:.0} N s/m) breaks {}",
                        all.join(" and "),
                        l.ks,
                        l.cs,
                        broken.join(" and ")
                    ),
                }
            }
            None => RideError::Numerical("no feasible design: nothing was evaluated".into()),
        }
    }
}
