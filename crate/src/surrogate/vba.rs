//! VBA, the variable-based approach: `S = f~(tau(x, a))`, the LoFi quarter car evaluated at
//! transformed design variables. Each variable is transformed on its own, in normalised
//! coordinates (`u` for Ks, `v` for Cs; same form for `v`):
//!
//! ```text
//! LTS  u' = a0 + a1 u
//! MTS  u' = a1 u
//! QTS  u' = a0 + a1 u + a2 u^2
//! ```
//!
//! and mapped back to physical values, `ks' = ks_min + u' (ks_max - ks_min)`, before the LoFi.
//! MTS in normalised coordinates keeps the box's lower edges fixed (`u = 0` maps to `u' = 0`),
//! so it cannot correct the LoFi at `ks = ks_min` or `cs = cs_min`.
//! Guard: a tuning is admissible only if `ks' > 0` and `cs' > 0` over the whole design box.

use super::fit::{check_tuning, LmOptions, Tuning};
use super::tuned::Tuned;
use super::{Approach, Sample, Scheme, Setting, SurrogateParams, SurrogateSpec, Transform};
use crate::car::QuarterCar;
use crate::design::DesignBox;
use crate::error::{Result, RideError};
use serde::{Deserialize, Serialize};

impl Transform {
    /// Coefficient names of one variable.
    fn coefficients(self) -> &'static [&'static str] {
        match self {
            Transform::Lts => &["a0", "a1"],
            Transform::Mts => &["a1"],
            Transform::Qts => &["a0", "a1", "a2"],
        }
    }

    /// The identity transform's coefficients.
    fn identity(self) -> &'static [f64] {
        match self {
            Transform::Lts => &[0.0, 1.0],
            Transform::Mts => &[1.0],
            Transform::Qts => &[0.0, 1.0, 0.0],
        }
    }

    /// `u'` for coefficients `c` (as many as [`Transform::coefficients`]).
    fn apply(self, c: &[f64], u: f64) -> f64 {
        match self {
            Transform::Lts => c[0] + c[1] * u,
            Transform::Mts => c[0] * u,
            Transform::Qts => c[0] + (c[1] + c[2] * u) * u,
        }
    }

    /// Least `u'` over `u` in [0, 1]: at an end or, for QTS, at the vertex `-a1 / (2 a2)`.
    fn min_on_unit(self, c: &[f64]) -> f64 {
        let ends = self.apply(c, 0.0).min(self.apply(c, 1.0));
        match self {
            Transform::Qts if c[2] != 0.0 => {
                let vertex = -c[1] / (2.0 * c[2]);
                if (0.0..=1.0).contains(&vertex) {
                    ends.min(self.apply(c, vertex))
                } else {
                    ends
                }
            }
            _ => ends,
        }
    }
}

/// The VBA tuning: `a = [Ks coefficients, Cs coefficients]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct VariableTuning {
    transform: Transform,
    design_box: DesignBox,
    base: QuarterCar,
}

impl VariableTuning {
    /// The tuning of `base` (the car's front quarter car) over `design_box`.
    pub fn new(transform: Transform, design_box: DesignBox, base: QuarterCar) -> Self {
        VariableTuning {
            transform,
            design_box,
            base,
        }
    }

    /// The Ks and Cs coefficient slices of `a`.
    fn split<'a>(&self, a: &'a [f64]) -> (&'a [f64], &'a [f64]) {
        a.split_at(self.transform.coefficients().len())
    }

    /// Transformed physical design `(ks', cs')` of `(ks, cs)`.
    pub(crate) fn transformed(&self, a: &[f64], ks: f64, cs: f64) -> (f64, f64) {
        let (ck, cc) = self.split(a);
        let (u, v) = self.design_box.normalize(ks, cs);
        self.design_box
            .scale(self.transform.apply(ck, u), self.transform.apply(cc, v))
    }
}

impl Tuning for VariableTuning {
    fn names(&self) -> Vec<String> {
        ["ks", "cs"]
            .iter()
            .flat_map(|v| {
                self.transform
                    .coefficients()
                    .iter()
                    .map(move |c| format!("{v}.{c}"))
            })
            .collect()
    }

    fn neutral(&self) -> Vec<f64> {
        [self.transform.identity(); 2].concat()
    }

    fn spread(&self) -> Vec<f64> {
        let one: &[f64] = match self.transform {
            Transform::Lts => &[0.1, 0.2],
            Transform::Mts => &[0.2],
            Transform::Qts => &[0.1, 0.2, 0.2],
        };
        [one; 2].concat()
    }

    /// `ks' > 0` and `cs' > 0` over the box: `u'_min > -ks_min / (ks_max - ks_min)`, same for Cs.
    fn admissible(&self, a: &[f64]) -> bool {
        let (ck, cc) = self.split(a);
        let b = &self.design_box;
        a.iter().all(|x| x.is_finite())
            && self.transform.min_on_unit(ck) > -b.ks_min / (b.ks_max - b.ks_min)
            && self.transform.min_on_unit(cc) > -b.cs_min / (b.cs_max - b.cs_min)
    }

    fn quarter(&self, a: &[f64], ks: f64, cs: f64) -> Result<QuarterCar> {
        let (ks_t, cs_t) = self.transformed(a, ks, cs);
        if !(ks_t > 0.0 && cs_t > 0.0) {
            return Err(RideError::field(
                "design",
                format!(
                    "the VBA transform maps (ks {ks}, cs {cs}) to (ks' {ks_t}, cs' {cs_t}); both must be > 0"
                ),
            ));
        }
        Ok(QuarterCar {
            ks: ks_t,
            cs: cs_t,
            ..self.base
        })
    }
}

/// Parameters of a VBA surrogate.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct VbaParams {
    /// The per-variable transform.
    pub transform: Transform,
    /// Shared or per-criterion tuning.
    pub scheme: Scheme,
    /// Levenberg-Marquardt settings.
    pub options: LmOptions,
}

impl VbaParams {
    fn spec(&self) -> SurrogateSpec {
        SurrogateSpec {
            approach: Approach::Vba(self.transform),
            scheme: self.scheme,
        }
    }
}

impl SurrogateParams for VbaParams {
    type Model = Tuned<VariableTuning>;

    fn check(&self, samples: &[Sample]) -> Result<()> {
        self.options.check()?;
        let c = self.transform.coefficients().len();
        check_tuning(2 * c, [c, c], samples, self.scheme, &self.spec().name())
    }

    fn fit(&self, setting: &Setting, samples: &[Sample]) -> Result<Self::Model> {
        self.check(samples)?;
        let tuning = VariableTuning::new(
            self.transform,
            setting.design_box,
            setting.lofi.car.quarter(),
        );
        Tuned::fit(
            self.spec(),
            tuning,
            &setting.lofi,
            samples,
            self.scheme,
            &self.options,
        )
    }
}
