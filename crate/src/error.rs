//! The one error type of the RideLab core. Every message names the field or
//! quantity at fault so the CLI and the page can show it next to that field.

use thiserror::Error;

/// Errors raised by the RideLab core.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum RideError {
    /// A named input field is missing, misspelt, of the wrong type or out of range.
    #[error("{field}: {reason}")]
    Field {
        /// Dotted path of the field, e.g. `front.spring`.
        field: String,
        /// Why it was rejected.
        reason: String,
    },
    /// No design in the box meets the design objectives: `field` names the binding
    /// objective's field (`sws_limit`, ...), `reason` says why (the closest any design came).
    #[error("{field}: {reason}")]
    Infeasible {
        /// The binding objective's field.
        field: String,
        /// Why nothing is feasible.
        reason: String,
    },
    /// A JSON document could not be parsed at all.
    #[error("invalid JSON: {0}")]
    Json(String),
    /// A computation cannot give a finite answer (for example an unstable model).
    #[error("{0}")]
    Numerical(String),
    /// The modal expansion does not apply to this model (repeated or unresolved modes, an
    /// asymmetric matrix): the exact Kronecker route does.
    #[error("modal: {0}")]
    ModalInapplicable(String),
    /// Independent tracks of unequal front and rear widths: the road warp makes the
    /// suspension deflections a random walk, unbounded in RMS over the whole band (the
    /// frequency route with ISO 8608's low cutoff applies).
    #[error("road warp: {0}")]
    RoadWarp(String),
    /// The GPU path cannot run: no adapter where one is required, a device or driver
    /// error, or a map larger than the device takes.
    #[error("GPU: {0}")]
    Gpu(String),
}

impl RideError {
    /// Shorthand for [`RideError::Field`].
    pub fn field(field: impl Into<String>, reason: impl Into<String>) -> Self {
        RideError::Field {
            field: field.into(),
            reason: reason.into(),
        }
    }
}

/// Result alias used across the crate.
pub type Result<T> = std::result::Result<T, RideError>;

/// `s` (blanks around it ignored, in any case) as the variant of `T` of that name or
/// alias (`#[strum(props(alias = "..."))]`), else an error naming `field` that lists the
/// names: `'x' is not 'a', 'b' or 'c'`. The names are strum's derives on `T`
/// (`IntoStaticStr`, `VariantNames`), so what parses and what the message lists cannot
/// drift apart from each other or from the enum.
pub(crate) fn parse_choice<T>(field: &str, s: &str) -> Result<T>
where
    T: strum::IntoEnumIterator + strum::VariantNames + strum::EnumProperty,
    for<'a> &'a T: Into<&'static str>,
{
    let t = s.trim();
    T::iter()
        .find(|v| names_it(v.into(), v.get_str("alias"), t))
        .ok_or_else(|| none_of(field, s, T::VARIANTS))
}

/// Whether `t` is `name` or `alias`, in any case (apart from [`parse_choice`], which is
/// made once per enum, so that this and [`none_of`] are made once).
pub(crate) fn names_it(name: &str, alias: Option<&str>, t: &str) -> bool {
    name.eq_ignore_ascii_case(t) || alias.is_some_and(|a| a.eq_ignore_ascii_case(t))
}

/// The refusal of `s` naming `field`: `'s' is not 'a', 'b' or 'c'`.
pub(crate) fn none_of(field: &str, s: &str, names: &[&str]) -> RideError {
    let names: Vec<String> = names.iter().map(|n| format!("'{n}'")).collect();
    let list = match names.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        _ => names.concat(),
    };
    RideError::field(field, format!("'{s}' is not {list}"))
}

#[cfg(test)]
mod tests {
    use crate::analysis::ModelKind;
    use crate::gpu::Compute;
    use crate::surrogate::infill::Infill;

    #[test]
    fn a_choice_parses_any_case_and_its_aliases_and_a_refusal_lists_every_name() {
        assert_eq!(ModelKind::parse(" HiFi ").unwrap(), ModelKind::Full);
        assert_eq!(ModelKind::parse("lofi").unwrap(), ModelKind::Quarter);
        assert_eq!("ehvi-front".parse::<Infill>().unwrap(), Infill::EhviFront);
        assert_eq!(Infill::EhviFront.name(), "ehvi-front");
        assert_eq!(
            Compute::parse("tpu").unwrap_err().to_string(),
            "compute: 'tpu' is not 'auto', 'gpu' or 'cpu'"
        );
        assert_eq!(
            ModelKind::parse("bicycle").unwrap_err().to_string(),
            "model: 'bicycle' is not 'quarter' or 'full'"
        );
    }
}
