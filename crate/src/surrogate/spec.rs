//! Names of surrogates and sampling plans, as the CLI and the page write them: the
//! approaches and the forms, transforms and scalings they are built from (the fits that
//! use them are in [`super::rba`], [`super::vba`] and [`super::pba`]; the dispatch from a
//! name to its fit in [`super::dispatch`]).
//!
//! Surrogates: `rba-{mul|add}-{poly1|poly2|rbf-gauss|rbf-mq|rbf-tps}`, `vba-{lts|mts|qts}`,
//! `pba-{smts|umts|kt, joined in that order}`, `data-{quad|lin|rbf-gauss|rbf-mq|rbf-tps}`,
//! `gp-mul` (the Gaussian-process correction, one model per criterion);
//! `rbf` alone means `rbf-gauss`. A `-per-criterion` suffix asks for one tuning per
//! criterion; without it the tuning is shared where the approach allows (VBA, PBA and the
//! multiplicative polynomial RBA), and per criterion otherwise.
//! Plans: `ae:N` (Audze-Eglais, N points), `grid:n` (n x n full factorial).

use super::response::{Kernel, ResponseKind};
use super::Scheme;
use crate::doe::{audze_eglais, full_factorial, Plan};
use crate::error::{Result, RideError};
use serde::{Deserialize, Serialize};

/// Suffix that selects the per-criterion scheme.
const PER_CRITERION: &str = "-per-criterion";

/// Seed of the Audze-Eglais heuristic (unused up to the tabulated 14 points).
const AE_SEED: u64 = 1;

/// How the correction acts on the LoFi output.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Form {
    /// `S = f~ tau`.
    Multiplicative,
    /// `S = f~ + d`.
    Additive,
}

impl Form {
    /// Name part: "mul" or "add".
    pub fn name(self) -> &'static str {
        match self {
            Form::Multiplicative => "mul",
            Form::Additive => "add",
        }
    }

    /// Whether this form with `response` can be shared by all criteria.
    pub(crate) fn shareable(self, response: ResponseKind) -> bool {
        self == Form::Multiplicative && matches!(response, ResponseKind::Poly(_))
    }
}

/// Form of the per-variable transform.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Transform {
    /// Linear `u' = a0 + a1 u`.
    Lts,
    /// Multiplicative `u' = a1 u`.
    Mts,
    /// Quadratic `u' = a0 + a1 u + a2 u^2`.
    Qts,
}

impl Transform {
    /// All transforms with their names.
    pub const ALL: [(Transform, &'static str); 3] = [
        (Transform::Lts, "lts"),
        (Transform::Mts, "mts"),
        (Transform::Qts, "qts"),
    ];

    /// Name: "lts", "mts" or "qts".
    pub fn name(self) -> &'static str {
        Transform::ALL
            .iter()
            .find(|(t, _)| *t == self)
            .map_or("", |(_, n)| n)
    }
}

/// Which LoFi parameters are scaled.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Scaling {
    /// Scale the sprung mass (SMTS).
    pub sprung: bool,
    /// Scale the unsprung mass (UMTS).
    pub unsprung: bool,
    /// Scale the tyre rate.
    pub tyre: bool,
}

impl Scaling {
    /// Name tokens in order, with the parameter each scales.
    pub(super) const TOKENS: [(&'static str, &'static str); 3] = [
        ("smts", "ms_scale"),
        ("umts", "mu_scale"),
        ("kt", "kt_scale"),
    ];

    pub(super) fn flags(self) -> [bool; 3] {
        [self.sprung, self.unsprung, self.tyre]
    }

    /// Name after "pba-": "smts", "umts", "smts-umts", "smts-umts-kt", ...
    pub fn name(self) -> String {
        Scaling::TOKENS
            .iter()
            .zip(self.flags())
            .filter(|(_, on)| *on)
            .map(|((t, _), _)| *t)
            .collect::<Vec<_>>()
            .join("-")
    }

    /// Every non-empty combination, for name lists and the study.
    pub fn all() -> Vec<Scaling> {
        (1..8u8)
            .map(|m| Scaling {
                sprung: m & 1 != 0,
                unsprung: m & 2 != 0,
                tyre: m & 4 != 0,
            })
            .collect()
    }

    pub(super) fn count(self) -> usize {
        self.flags().iter().filter(|&&on| on).count()
    }
}

/// The surrogate approaches (METHOD.md section 5).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Approach {
    /// Response-based correction of the LoFi output.
    Rba {
        /// Multiplicative or additive.
        form: Form,
        /// Polynomial or RBF correction.
        response: ResponseKind,
    },
    /// Variable-based: transformed design variables.
    Vba(Transform),
    /// Parameter-based: scaled LoFi parameters.
    Pba(Scaling),
    /// Data fit on the HiFi samples alone (baseline).
    Data(ResponseKind),
    /// Gaussian-process correction `S = f~ exp(g)`, `g` Kriging of `ln(F / f~)`
    /// ([`super::gp`]), with its own predictive variance.
    Gp,
}

impl Approach {
    /// Every approach the names can express, in the study's order.
    pub fn all() -> Vec<Approach> {
        let responses: Vec<ResponseKind> = [ResponseKind::Poly(1), ResponseKind::Poly(2)]
            .into_iter()
            .chain(Kernel::ALL.iter().map(|&(k, _)| ResponseKind::Rbf(k)))
            .collect();
        let mut all: Vec<Approach> = [Form::Multiplicative, Form::Additive]
            .into_iter()
            .flat_map(|form| {
                responses
                    .iter()
                    .map(move |&response| Approach::Rba { form, response })
            })
            .collect();
        all.extend(Transform::ALL.iter().map(|&(t, _)| Approach::Vba(t)));
        all.extend(Scaling::all().into_iter().map(Approach::Pba));
        all.extend(responses.iter().map(|&r| Approach::Data(r)));
        all.push(Approach::Gp);
        all
    }

    /// Whether one tuning can serve all three criteria.
    pub(crate) fn shareable(self) -> bool {
        match self {
            Approach::Rba { form, response } => form.shareable(response),
            Approach::Vba(_) | Approach::Pba(_) => true,
            Approach::Data(_) | Approach::Gp => false,
        }
    }

    /// The name without scheme suffix, e.g. "rba-mul-poly2", "pba-smts-umts", "data-quad".
    pub fn name(self) -> String {
        match self {
            Approach::Rba { form, response } => format!("rba-{}-{}", form.name(), response.name()),
            Approach::Vba(t) => format!("vba-{}", t.name()),
            Approach::Pba(s) => format!("pba-{}", s.name()),
            Approach::Data(ResponseKind::Poly(2)) => "data-quad".into(),
            Approach::Data(ResponseKind::Poly(_)) => "data-lin".into(),
            Approach::Data(r) => format!("data-{}", r.name()),
            Approach::Gp => "gp-mul".into(),
        }
    }

    /// Parses a name made by [`Approach::name`]; `rbf` alone means `rbf-gauss`.
    fn parse(s: &str) -> Option<Approach> {
        let s = match s.strip_suffix("-rbf") {
            Some(head) => format!("{head}-rbf-gauss"),
            None => s.to_string(),
        };
        Approach::all().into_iter().find(|a| a.name() == s)
    }
}

/// A surrogate to fit: approach and scheme.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct SurrogateSpec {
    /// The approach.
    pub approach: Approach,
    /// Shared or per-criterion tuning.
    pub scheme: Scheme,
}

impl SurrogateSpec {
    /// Parses a surrogate name (see the module doc). Unknown names give an error naming
    /// `approach` that lists the valid names.
    pub fn parse(name: &str) -> Result<SurrogateSpec> {
        let lower = name.trim().to_ascii_lowercase();
        let (base, per) = match lower.strip_suffix(PER_CRITERION) {
            Some(b) => (b, true),
            None => (lower.as_str(), false),
        };
        let approach = Approach::parse(base).ok_or_else(|| {
            let valid: Vec<String> = Approach::all().into_iter().map(Approach::name).collect();
            RideError::field(
                "approach",
                format!(
                    "'{name}' is not a surrogate; valid: {} (optionally with '{PER_CRITERION}'; 'rbf' means 'rbf-gauss')",
                    valid.join(", ")
                ),
            )
        })?;
        let scheme = if per || !approach.shareable() {
            Scheme::PerCriterion
        } else {
            Scheme::Shared
        };
        Ok(SurrogateSpec { approach, scheme })
    }

    /// Canonical name: the approach, plus `-per-criterion` where the approach could be shared.
    pub fn name(&self) -> String {
        let suffix = if self.scheme == Scheme::PerCriterion && self.approach.shareable() {
            PER_CRITERION
        } else {
            ""
        };
        format!("{}{suffix}", self.approach.name())
    }

    /// Every approach with every scheme it offers, in the study's order.
    pub fn all() -> Vec<SurrogateSpec> {
        Approach::all()
            .into_iter()
            .flat_map(|approach| {
                let schemes: &[Scheme] = if approach.shareable() {
                    &[Scheme::Shared, Scheme::PerCriterion]
                } else {
                    &[Scheme::PerCriterion]
                };
                schemes
                    .iter()
                    .map(move |&scheme| SurrogateSpec { approach, scheme })
            })
            .collect()
    }
}

/// A named sampling plan.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "kind", content = "n", rename_all = "kebab-case")]
pub enum PlanSpec {
    /// Audze-Eglais Latin hypercube of `n` points (`ae:n`).
    AudzeEglais(usize),
    /// `n x n` full factorial grid (`grid:n`).
    Grid(usize),
}

impl std::str::FromStr for PlanSpec {
    type Err = RideError;
    fn from_str(s: &str) -> Result<PlanSpec> {
        PlanSpec::parse(s)
    }
}

impl std::str::FromStr for SurrogateSpec {
    type Err = RideError;
    fn from_str(s: &str) -> Result<SurrogateSpec> {
        SurrogateSpec::parse(s)
    }
}

impl PlanSpec {
    /// The seed's study: Audze-Eglais with 2, 3, 4, 5 and 10 points, then the grids with
    /// the same numbers of levels.
    pub fn study() -> Vec<PlanSpec> {
        let n = [2, 3, 4, 5, 10];
        n.iter()
            .map(|&n| PlanSpec::AudzeEglais(n))
            .chain(n.iter().map(|&n| PlanSpec::Grid(n)))
            .collect()
    }

    /// Parses `ae:N` or `grid:n`; errors name `plan`.
    pub fn parse(s: &str) -> Result<PlanSpec> {
        let bad = || {
            RideError::field(
                "plan",
                format!("'{s}' is not a plan; write 'ae:N' (Audze-Eglais, N points) or 'grid:n' (n x n grid)"),
            )
        };
        let lower = s.trim().to_ascii_lowercase();
        let (kind, n) = lower.split_once(':').ok_or_else(bad)?;
        let n: usize = n.trim().parse().map_err(|_| bad())?;
        match kind.trim() {
            "ae" => Ok(PlanSpec::AudzeEglais(n)),
            "grid" => Ok(PlanSpec::Grid(n)),
            _ => Err(bad()),
        }
    }

    /// Name: `ae:N` or `grid:n`.
    pub fn name(&self) -> String {
        match self {
            PlanSpec::AudzeEglais(n) => format!("ae:{n}"),
            PlanSpec::Grid(n) => format!("grid:{n}"),
        }
    }

    /// The plan on the unit square; errors (naming `plan`) for sizes the DOE refuses.
    pub fn plan(&self) -> Result<Plan> {
        match self {
            PlanSpec::AudzeEglais(n) => audze_eglais(*n, AE_SEED),
            PlanSpec::Grid(n) => full_factorial(*n),
        }
        .map_err(|e| RideError::field("plan", format!("{}: {e}", self.name())))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_defaults() {
        for spec in SurrogateSpec::all() {
            assert_eq!(
                SurrogateSpec::parse(&spec.name()).unwrap(),
                spec,
                "{}",
                spec.name()
            );
        }
        let s = SurrogateSpec::parse("vba-qts").unwrap();
        assert_eq!(
            (s.approach, s.scheme),
            (Approach::Vba(Transform::Qts), Scheme::Shared)
        );
        let s = SurrogateSpec::parse("PBA-SMTS-UMTS-KT-per-criterion").unwrap();
        assert_eq!(s.scheme, Scheme::PerCriterion);
        assert_eq!(s.name(), "pba-smts-umts-kt-per-criterion");
        // Inherently per-criterion approaches take the suffix silently.
        let a = SurrogateSpec::parse("rba-add-poly1").unwrap();
        assert_eq!(
            a,
            SurrogateSpec::parse("rba-add-poly1-per-criterion").unwrap()
        );
        assert_eq!(a.name(), "rba-add-poly1");
        assert_eq!(
            SurrogateSpec::parse("data-rbf").unwrap().name(),
            "data-rbf-gauss"
        );
        for name in [
            "rba-mul-poly2",
            "rba-mul-rbf-gauss",
            "vba-lts",
            "vba-mts",
            "pba-smts",
            "pba-umts",
            "pba-smts-umts",
            "data-quad",
            "gp-mul",
        ] {
            assert_eq!(SurrogateSpec::parse(name).unwrap().name(), name);
        }
    }

    #[test]
    fn bad_names_list_the_valid_ones() {
        for bad in [
            "vba-cts",
            "rba-mul-poly3",
            "pba-umts-smts",
            "pba",
            "",
            "data-quad-shared",
        ] {
            let e = SurrogateSpec::parse(bad).unwrap_err().to_string();
            assert!(e.starts_with("approach: "), "{e}");
            assert!(
                e.contains("vba-qts") && e.contains("pba-smts-umts-kt"),
                "{e}"
            );
        }
        assert_eq!(PlanSpec::parse("ae:10").unwrap(), PlanSpec::AudzeEglais(10));
        assert_eq!(PlanSpec::parse(" GRID:5 ").unwrap().name(), "grid:5");
        for bad in ["ae", "lhs:4", "grid:x", "ae:-1"] {
            assert!(PlanSpec::parse(bad)
                .unwrap_err()
                .to_string()
                .starts_with("plan: "));
        }
        let e = PlanSpec::parse("ae:1")
            .unwrap()
            .plan()
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("plan: ae:1"), "{e}");
    }
}
