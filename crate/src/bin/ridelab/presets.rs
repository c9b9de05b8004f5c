//! `ridelab presets`: the shipped cars with their sources.

use crate::args::json;
use clap::Args;
use ridelab::car::Car;
use ridelab::error::Result;

#[derive(Args)]
pub(crate) struct PresetsArgs {
    /// The cars as JSON (`cars`, SI units, with a `units` object) instead of the list.
    #[arg(long)]
    pub(crate) json: bool,
}

pub(crate) fn presets(a: PresetsArgs) -> Result<String> {
    let cars: Vec<Car> = ridelab::car::PRESETS
        .iter()
        .map(|(n, _)| Car::preset(n))
        .collect::<Result<_>>()?;
    if a.json {
        return json(&serde_json::json!({ "cars": cars }));
    }
    Ok(ridelab::car::PRESETS
        .iter()
        .zip(&cars)
        .map(|((n, _), c)| format!("{n:<8} {}\n         source: {}\n", c.name, c.source))
        .collect())
}
