//! The explorer's one model type (issue #28): which model answers a map, a front, the
//! criteria of a design or a slider step. Before, each of those had its own enum
//! (`MapModel`, `FrontModel`, `EvaluatorKind`) naming the same models; now each use
//! says which of [`Model`]'s variants it takes ([`Model::MAP`], [`Model::FRONT`],
//! [`Model::CRITERIA`]) and refuses the others by name, as the old enums' parsers did.
//! Beneath it, [`crate::analysis::ModelKind`] stays the physical model a criteria route
//! builds (quarter or full car), as the CLI's `--model` names it.

use crate::error::{names_it, none_of, Result, RideError};
use serde::Serialize;
use strum::{EnumProperty, IntoStaticStr};

/// A model of the explorer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, EnumProperty, IntoStaticStr)]
#[serde(rename_all = "lowercase")]
#[strum(serialize_all = "lowercase")]
pub enum Model {
    /// The quarter car (closed forms).
    #[strum(serialize = "lofi", props(alias = "quarter"))]
    LoFi,
    /// The full car (the maps' fast exact route).
    #[strum(serialize = "hifi", props(alias = "full"))]
    HiFi,
    /// The scenario's fitted surrogate (its BAcc the unweighted one it was fitted to).
    Surrogate,
    /// The surrogate's signed relative error against the HiFi, % (a map only).
    #[serde(rename = "error")]
    #[strum(serialize = "error")]
    SurrogateError,
    /// With robust cases, the quarter car's robust objective over the cases, as the
    /// robust front's problem sees it (each case scaled to its HiFi datum:
    /// [`crate::study::robust::optimize::hifi_combination`]).
    Robust,
}

impl Model {
    /// The models a map shows (`Session::map`).
    pub const MAP: &'static [Model] = &[
        Model::LoFi,
        Model::HiFi,
        Model::Surrogate,
        Model::SurrogateError,
        Model::Robust,
    ];
    /// The models a front is found on (`Session::front`); the HiFi's own front is
    /// `hifi_front`'s.
    pub const FRONT: &'static [Model] = &[Model::LoFi, Model::Surrogate, Model::Robust];
    /// The models that give a design's criteria (`Session::criteria`, the plane of
    /// `Session::design_step`).
    pub const CRITERIA: &'static [Model] =
        &[Model::LoFi, Model::HiFi, Model::Surrogate, Model::Robust];

    /// Parses one of `among` by its name or alias, in any case, surrounding blanks
    /// ignored; anything else is refused naming `field` with the names of `among`
    /// (`'x' is not 'lofi', 'surrogate' or 'robust'`).
    pub fn parse_among(field: &str, s: &str, among: &[Model]) -> Result<Model> {
        let t = s.trim();
        among
            .iter()
            .copied()
            .find(|m| names_it(m.into(), m.get_str("alias"), t))
            .ok_or_else(|| none_of(field, s, &names(among)))
    }

    /// Why this model cannot answer where only `among` can: the error naming `field`.
    pub fn refused(self, field: &str, among: &[Model]) -> RideError {
        none_of(field, self.into(), &names(among))
    }
}

/// The names of `models`, in their order.
fn names(models: &[Model]) -> Vec<&'static str> {
    models.iter().map(|m| m.into()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_use_takes_its_models_and_names_them_when_refusing() {
        assert_eq!(
            Model::parse_among("model", " HiFi ", Model::MAP).unwrap(),
            Model::HiFi
        );
        assert_eq!(
            Model::parse_among("model", "quarter", Model::CRITERIA).unwrap(),
            Model::LoFi
        );
        assert_eq!(
            Model::parse_among("model", "error", Model::MAP).unwrap(),
            Model::SurrogateError
        );
        // The messages the three enums this replaces gave, word for word.
        let e = Model::parse_among("frontModel", "hifi", Model::FRONT).unwrap_err();
        assert_eq!(
            e.to_string(),
            "frontModel: 'hifi' is not 'lofi', 'surrogate' or 'robust'"
        );
        let e = Model::parse_among("model", "error", Model::CRITERIA).unwrap_err();
        assert_eq!(
            e.to_string(),
            "model: 'error' is not 'lofi', 'hifi', 'surrogate' or 'robust'"
        );
        let e = Model::parse_among("model", "x", Model::MAP).unwrap_err();
        assert_eq!(
            e.to_string(),
            "model: 'x' is not 'lofi', 'hifi', 'surrogate', 'error' or 'robust'"
        );
        // A model a Rust caller passes where it cannot answer: the same refusal.
        let e = Model::SurrogateError.refused("model", Model::CRITERIA);
        assert_eq!(
            e.to_string(),
            "model: 'error' is not 'lofi', 'hifi', 'surrogate' or 'robust'"
        );
    }
}
