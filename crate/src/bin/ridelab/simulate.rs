//! `ridelab simulate`: a time response on a seeded road realisation.

use crate::args::{car_and_road, car_loads_road_of, count, count_u64, number, CarRoad};
use crate::units::json_with_units;
use clap::Args;
use ridelab::analysis::ModelKind;
use ridelab::car::Car;
use ridelab::error::{Result, RideError};
use ridelab::road::Road;
use ridelab::road_profile::playback;
use ridelab::time_domain::{simulate, simulate_playback, Damper, Knee, TimeOptions, TimeResponse};
use serde::Serialize;
use std::collections::BTreeMap;

#[derive(Args)]
pub(crate) struct SimulateArgs {
    /// quarter (LoFi) or full (HiFi).
    #[arg(long)]
    pub(crate) model: ModelKind,
    /// Length of the road record, s.
    #[arg(long, value_name = "S", default_value_t = TimeOptions::default().duration, value_parser = number, allow_negative_numbers = true)]
    pub(crate) duration: f64,
    /// Time step, s (the road's highest frequency follows it: at most 0.4 / dt).
    #[arg(long, value_name = "S", value_parser = number, allow_negative_numbers = true)]
    pub(crate) dt: Option<f64>,
    /// Seed of the road's random phases.
    #[arg(long, default_value_t = 1, value_parser = count_u64, allow_negative_numbers = true)]
    pub(crate) seed: u64,
    /// Front damper bump (compression) rate, N s/m; the design's Cs is then the mean
    /// of bump and rebound, so --cs is left out.
    #[arg(long, value_name = "NS/M", value_parser = number, allow_negative_numbers = true, requires = "rebound")]
    pub(crate) bump: Option<f64>,
    /// Front damper rebound (extension) rate, N s/m.
    #[arg(long, value_name = "NS/M", value_parser = number, allow_negative_numbers = true, requires = "bump")]
    pub(crate) rebound: Option<f64>,
    /// Knee velocity of a digressive damper, m/s.
    #[arg(long, value_name = "M/S", value_parser = number, allow_negative_numbers = true, requires_all = ["bump", "bump_high", "rebound_high"])]
    pub(crate) knee: Option<f64>,
    /// Bump slope above the knee, N s/m.
    #[arg(long, value_name = "NS/M", value_parser = number, allow_negative_numbers = true, requires = "knee")]
    pub(crate) bump_high: Option<f64>,
    /// Rebound slope above the knee, N s/m.
    #[arg(long, value_name = "NS/M", value_parser = number, allow_negative_numbers = true, requires = "knee")]
    pub(crate) rebound_high: Option<f64>,
    /// Keep every n-th sample in the output.
    #[arg(long, default_value_t = 10, value_parser = count, allow_negative_numbers = true)]
    pub(crate) decimate: usize,
    #[command(flatten)]
    pub(crate) car: CarRoad,
    /// Machine-readable output (JSON).
    #[arg(long, conflicts_with = "csv")]
    pub(crate) json: bool,
    /// One row per kept sample (CSV) instead of the text summary.
    #[arg(long)]
    pub(crate) csv: bool,
}

/// The front damper law of `--bump --rebound [--knee --bump-high --rebound-high]`
/// (clap makes sure they come together); the core's field names become the options'.
pub(crate) fn damper_law(a: &SimulateArgs) -> Result<Option<Damper>> {
    let (Some(bump), Some(rebound)) = (a.bump, a.rebound) else {
        return Ok(None);
    };
    let knee = match (a.knee, a.bump_high, a.rebound_high) {
        (Some(velocity), Some(bump), Some(rebound)) => Some(Knee {
            velocity,
            bump,
            rebound,
        }),
        _ => None,
    };
    let law = Damper {
        bump,
        rebound,
        knee,
    };
    law.validate().map_err(|e| match e {
        RideError::Field { field, reason } => {
            let option = match field.as_str() {
                "knee.velocity" => "knee",
                "knee.bump" => "bump-high",
                "knee.rebound" => "rebound-high",
                other => other,
            };
            RideError::field(option, reason)
        }
        other => other,
    })?;
    if let Some(cs) = a.car.cs {
        law.check_design_cs(cs)?;
    }
    Ok(Some(law))
}

pub(crate) fn simulate_cmd(a: SimulateArgs) -> Result<String> {
    if let Some(path) = a.car.road.as_deref() {
        return simulate_road(&a, path);
    }
    let (car, road) = car_and_road(&a.car)?;
    let mut opt = TimeOptions {
        duration: a.duration,
        seed: a.seed,
        decimate: a.decimate,
        damper: damper_law(&a)?,
        ..TimeOptions::default()
    };
    if let Some(dt) = a.dt {
        opt = opt.with_step(dt);
    }
    let r = simulate(a.model, &car, &road, &opt)?;
    simulate_output(&a, &car, &r, &opt, None)
}

/// `simulate --road FILE`: the profile itself played back under the wheels at `--speed`
/// (rear wheels a wheelbase later), from rest at its start, for as long as every wheel
/// is on it (`--duration` and `--seed` do not apply; `--tracks` is refused: a two-track
/// file plays each track under its wheels, a one-track file plays on both). The step is
/// the largest at most `--dt` that divides the profile's spacing at the speed.
fn simulate_road(a: &SimulateArgs, path: &str) -> Result<String> {
    if a.car.tracks.is_some() {
        return Err(RideError::field(
            "tracks",
            "a played-back profile drives each track with its own column (one column: both); leave out --tracks with --road",
        ));
    }
    let (car, _, _) = car_loads_road_of(&a.car)?;
    let profile = crate::road::read_profile(path)?;
    let speed = a.car.speed.unwrap_or(Road::default().speed);
    ridelab::domain::SPEED.check("speed", speed)?;
    let max_dt = a.dt.unwrap_or(TimeOptions::default().dt);
    if !(max_dt > 0.0 && max_dt <= 0.01) {
        return Err(RideError::field("dt", "must be in (0, 0.01] s"));
    }
    let dt = profile.playback_step(speed, max_dt);
    let wheels = playback(&profile, &a.model.build(&car).wheels, speed, dt)?;
    if wheels.len() as f64 > ridelab::time_domain::MAX_STEPS {
        return Err(RideError::field(
            "road",
            format!(
                "the playback takes {} steps of {dt:.3e} s; at most {:e}: a faster --speed or a longer --dt",
                wheels.len(),
                ridelab::time_domain::MAX_STEPS
            ),
        ));
    }
    let opt = TimeOptions {
        dt,
        duration: (wheels.len() - 1) as f64 * dt,
        decimate: a.decimate,
        damper: damper_law(a)?,
        ..TimeOptions::default()
    };
    let r = simulate_playback(a.model, &car, dt, &wheels.wheels, &opt)?;
    simulate_output(a, &car, &r, &opt, Some(path))
}

/// The JSON, CSV or text of a run.
fn simulate_output(
    a: &SimulateArgs,
    car: &Car,
    r: &TimeResponse,
    opt: &TimeOptions,
    road_file: Option<&str>,
) -> Result<String> {
    if a.json {
        let dofs = a.model.build(car).dof_names;
        let mut j = SimulateJson::new(r, opt, &dofs);
        j.road_file = road_file.map(str::to_string);
        return json_with_units(&j);
    }
    if a.csv {
        ridelab::finite::check(r)?;
        return Ok(simulate_csv(r));
    }
    let k = |v: f64| v / 1e3;
    let damper = match opt.damper {
        None => format!("linear front damper Cs {} kNs/m", k(r.damper_rate)),
        Some(law) => format!(
            "front damper bump {} / rebound {} kNs/m{}: Cs = their mean {} kNs/m, energy-equivalent rate over the run {:.4} kNs/m",
            k(law.bump),
            k(law.rebound),
            law.knee.map_or(String::new(), |kn| format!(
                " (knee {} m/s, then {} / {} kNs/m)",
                kn.velocity,
                k(kn.bump),
                k(kn.rebound)
            )),
            k(r.damper_rate),
            k(r.equivalent_rate)
        ),
    };
    let on = road_file.map_or(String::new(), |f| {
        format!("the measured road {f} played back from rest at its start, ")
    });
    Ok(format!(
        "{on}{} s at {} s steps: RMS BAcc {:.5} m/s^2, DTL {:.3} N, SWS {:.4} mm\n{damper}\n",
        opt.duration,
        opt.dt,
        r.rms[0],
        r.rms[1],
        1e3 * r.rms[2]
    ))
}

pub(crate) fn simulate_csv(r: &TimeResponse) -> String {
    let mut s = String::from("t_s,road_m,bacc_m_per_s2,dtl_n,sws_m\n");
    for i in 0..r.t.len() {
        s += &format!(
            "{},{},{},{},{}\n",
            r.t[i], r.road[i], r.outputs[0][i], r.outputs[1][i], r.outputs[2][i]
        );
    }
    s
}

/// `simulate --json`: every series named, the step stated.
#[derive(Serialize)]
struct SimulateJson<'a> {
    /// Time step of the integration, s (every sample enters the RMS).
    dt: f64,
    /// Time between kept samples, s (`dt` x `decimate`).
    sample_interval: f64,
    duration: f64,
    seed: u64,
    decimate: usize,
    /// Kept samples: `t`, `road` (under the front-right wheel), `bacc`, `dtl`, `sws`.
    series: BTreeMap<&'static str, &'a [f64]>,
    /// Generalised coordinates by name (m or rad).
    positions: BTreeMap<String, &'a [f64]>,
    /// Their accelerations by name (m/s^2 or rad/s^2).
    accelerations: BTreeMap<String, &'a [f64]>,
    /// RMS of each output over the whole record.
    rms: BTreeMap<&'static str, f64>,
    damper_rate: f64,
    equivalent_rate: f64,
    /// The measured profile played back (`--road FILE`); left out on an ISO road.
    #[serde(skip_serializing_if = "Option::is_none")]
    road_file: Option<String>,
}

impl<'a> SimulateJson<'a> {
    fn new(r: &'a TimeResponse, opt: &TimeOptions, dofs: &[&str]) -> Self {
        let key = |name: &str| name.replace([' ', '-'], "_");
        let named = |rows: &'a [Vec<f64>]| -> BTreeMap<String, &'a [f64]> {
            dofs.iter()
                .zip(rows)
                .map(|(d, v)| (key(d), v.as_slice()))
                .collect()
        };
        let out = ["bacc", "dtl", "sws"];
        let mut series: BTreeMap<&'static str, &'a [f64]> = out
            .iter()
            .zip(&r.outputs)
            .map(|(k, v)| (*k, v.as_slice()))
            .collect();
        series.insert("t", &r.t);
        series.insert("road", &r.road);
        SimulateJson {
            dt: opt.dt,
            sample_interval: opt.dt * opt.decimate as f64,
            duration: opt.duration,
            seed: opt.seed,
            decimate: opt.decimate,
            series,
            positions: named(&r.positions),
            accelerations: named(&r.accelerations),
            rms: out.iter().zip(r.rms).map(|(k, v)| (*k, v)).collect(),
            damper_rate: r.damper_rate,
            equivalent_rate: r.equivalent_rate,
            road_file: None,
        }
    }
}
