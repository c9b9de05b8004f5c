//! `ridelab eval`: one design by both routes, modes and ride properties.

use crate::args::{car_and_road, json, CarRoad};
use clap::Args;
use ridelab::analysis::{report, ModelKind, Report};
use ridelab::error::Result;

#[derive(Args)]
pub(crate) struct EvalArgs {
    /// quarter (LoFi) or full (HiFi).
    #[arg(long)]
    pub(crate) model: ModelKind,
    #[command(flatten)]
    pub(crate) car: CarRoad,
    /// The evaluation as JSON (SI units, with a `units` object) instead of the text.
    #[arg(long)]
    pub(crate) json: bool,
}

pub(crate) fn eval(a: EvalArgs) -> Result<String> {
    if let Some(path) = a.car.road.as_deref() {
        let (car, _, _) = crate::args::car_loads_road_of(&a.car)?;
        // The car's own design too: the model is prepared on it, as map and optimize
        // prepare theirs, so that eval gives their values bit for bit.
        let own = CarRoad {
            ks: None,
            cs: None,
            ..a.car.clone()
        };
        let (datum, _, _) = crate::args::car_loads_road_of(&own)?;
        let r = crate::road::eval_measured(a.model, &datum, &car, &a.car, path)?;
        return if a.json {
            json(&r)
        } else {
            ridelab::finite::check(&r)?;
            Ok(crate::road::measured_text(&r))
        };
    }
    let (car, road) = car_and_road(&a.car)?;
    let r = report(a.model, &car, &road)?;
    if a.json {
        json(&r)
    } else {
        Ok(text_report(&r))
    }
}

pub(crate) fn text_report(r: &Report) -> String {
    let mut s = format!(
        "{} model, {} on {}\nKs {:.3} kN/m, Cs {:.4} kNs/m\n\
         BAcc {:.5} m/s^2 (ISO 2631-1 Wk-weighted {:.5} m/s^2: {})\n\
         DTL  {:.3} N ({:.2} % of static wheel load)\nSWS  {:.4} mm\n\
         route {}\n",
        match r.model {
            ModelKind::Quarter => "Quarter-car (LoFi)",
            ModelKind::Full => "Full-car (HiFi)",
        },
        r.car,
        crate::text::scenario_words(&r.road),
        r.ks / 1e3,
        r.cs / 1e3,
        r.bacc,
        r.bacc_wk,
        r.comfort,
        r.dtl,
        100.0 * r.dtl_relative,
        1e3 * r.sws,
        match r.route_difference {
            Some(d) => format!("{} (the frequency route differs by {d:.1e})", r.route),
            None => format!(
                "{} only (no exact route with road warp to check it against; its own error estimate {:.1e})",
                r.route, r.spectral_error_estimate.unwrap_or(0.0)
            ),
        }
    );
    if let Some(f) = r.low_cutoff_hz {
        s += &format!("note: road warp; band starts at ISO 8608's 0.011 cycle/m = {f:.3} Hz\n");
    }
    s += &format!(
        "body bounce {:.3} Hz, damping ratio {:.3}, critical damping {:.3} kNs/m, wheel rate {:.3} kN/m\nmodes:\n",
        r.body_bounce_hz, r.damping_ratio, r.critical_damping / 1e3, r.wheel_rate / 1e3
    );
    for m in &r.modes {
        s += &format!(
            "  {:>7.3} Hz  zeta {:.3}  {}\n",
            m.frequency, m.damping_ratio, m.label
        );
    }
    s
}
