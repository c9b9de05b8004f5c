//! `ridelab doe`: an Audze-Eglais plan in the default design box.

use crate::args::{count, count_u64, json};
use clap::Args;
use ridelab::design::DesignBox;
use ridelab::doe::doe_report;
use ridelab::error::Result;

#[derive(Args)]
pub(crate) struct DoeArgs {
    /// Number of points, 2..1000.
    #[arg(long, value_parser = count, allow_negative_numbers = true)]
    pub(crate) points: usize,
    /// Seed of the annealing (plans beyond the stored optima).
    #[arg(long, default_value_t = 1, value_parser = count_u64, allow_negative_numbers = true)]
    pub(crate) seed: u64,
    /// Machine-readable output (JSON).
    #[arg(long)]
    pub(crate) json: bool,
}

pub(crate) fn doe(a: DoeArgs) -> Result<String> {
    let r = doe_report(a.points, a.seed, &DesignBox::default())?;
    if a.json {
        return json(&r);
    }
    let mut s = format!(
        "Audze-Eglais plan, {} points ({}, {}), energy {:.6}\n  level   Ks N/m      Cs N s/m\n",
        r.points,
        r.method,
        if r.optimal { "optimal" } else { "heuristic" },
        r.energy
    );
    for p in &r.samples {
        s += &format!(
            "  {:>2},{:<2}  {:>9.1}  {:>9.1}\n",
            p.level[0], p.level[1], p.ks, p.cs
        );
    }
    Ok(s)
}
