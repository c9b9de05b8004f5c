//! What several commands share: the car, road and design options, the design box, the
//! objectives, the cases and the adaptive loop; number parsers; the output helpers.

use clap::Args;
use ridelab::car::Car;
use ridelab::design::DesignBox;
use ridelab::dos::DesignObjectives;
use ridelab::error::{Result, RideError};
use ridelab::optimize::Warning;
use ridelab::road::{Road, RoadClass, Tracks};
use ridelab::robust::{CarFile, CaseSet, Combine, LoadCase};
use ridelab::study::adaptive::{AdaptiveOptions, DEFAULT_CANDIDATES, DEFAULT_MIN_DISTANCE};
use ridelab::study::spec::one_scenario;
use ridelab::study::{MeasuredSource, StudyRoad, StudySpec};
use ridelab::surrogate::infill::Infill;
use ridelab::surrogate::uncertainty::UncertaintyMethod;
use std::path::{Path, PathBuf};

/// The car, the road and the front design.
#[derive(Args, Clone)]
pub(crate) struct CarRoad {
    /// A car file (JSON) or a preset name: sedan (the datum), compact, suv.
    #[arg(long, value_name = "FILE|PRESET")]
    pub(crate) car: Option<String>,
    /// ISO 8608 road class A..H [default: B].
    #[arg(long)]
    pub(crate) class: Option<RoadClass>,
    /// A measured road profile (CSV distance_m,elevation_m[,elevation_right_m]) in place
    /// of --class on eval, map, optimize, surrogate, study, simulate and report; see
    /// `ridelab road FILE`.
    #[arg(long, value_name = "FILE", conflicts_with = "class")]
    pub(crate) road: Option<String>,
    /// Speed, m/s [default: 20].
    #[arg(long, value_name = "M/S", value_parser = number, allow_negative_numbers = true)]
    pub(crate) speed: Option<f64>,
    /// Left and right tracks: correlated or independent [default: correlated].
    #[arg(long)]
    pub(crate) tracks: Option<Tracks>,
    /// Front spring rate, N/m [default: the car's].
    #[arg(long, value_name = "N/M", value_parser = number, allow_negative_numbers = true)]
    pub(crate) ks: Option<f64>,
    /// Front damper rate, N s/m [default: the car's].
    #[arg(long, value_name = "NS/M", value_parser = number, allow_negative_numbers = true)]
    pub(crate) cs: Option<f64>,
}

/// The cases of a robust design (issue #16), map and optimize.
#[derive(Args)]
pub(crate) struct CasesArgs {
    /// A cases file (JSON): load cases, operating points (class, speed, weight) and
    /// combine (worst or mean); the design is then robust over every case. A car file
    /// that lists load_cases makes it robust over them too.
    #[arg(long, value_name = "FILE")]
    pub(crate) cases: Option<String>,
}

impl CasesArgs {
    /// The case set when there is more than the car as given: `--cases`, or the car
    /// file's load cases at `--class`/`--speed`.
    pub(crate) fn set(
        &self,
        car: &Car,
        loads: &[LoadCase],
        road: &Road,
    ) -> Result<Option<CaseSet>> {
        match self.cases.as_deref() {
            Some(path) => {
                let text = std::fs::read_to_string(path)
                    .map_err(|e| RideError::field("cases", format!("cannot read '{path}': {e}")))?;
                CaseSet::from_json(&text, car, loads, road).map(Some)
            }
            None if loads.is_empty() => Ok(None),
            None => CaseSet::new(car, road, loads, &[], Combine::Worst).map(Some),
        }
    }
}

/// The design box (optimize, surrogate, report).
#[derive(Args)]
pub(crate) struct BoxArgs {
    /// Ks range of the design box, min:max (N/m).
    #[arg(long, value_name = "MIN:MAX", default_value = "10000:40000", allow_hyphen_values = true, value_parser = |s: &str| DesignBox::parse_range("ks-range", s))]
    pub(crate) ks_range: (f64, f64),
    /// Cs range of the design box, min:max (N s/m).
    #[arg(long, value_name = "MIN:MAX", default_value = "500:4000", allow_hyphen_values = true, value_parser = |s: &str| DesignBox::parse_range("cs-range", s))]
    pub(crate) cs_range: (f64, f64),
}

impl BoxArgs {
    /// The box, checked against the domain (errors name `ks-range` or `cs-range`).
    pub(crate) fn design_box(&self) -> Result<DesignBox> {
        let b = DesignBox {
            ks_min: self.ks_range.0,
            ks_max: self.ks_range.1,
            cs_min: self.cs_range.0,
            cs_max: self.cs_range.1,
        };
        b.validate()?;
        Ok(b)
    }
}

/// Design objectives beyond the defaults (map, optimize, report; surrogate and study with
/// `--adaptive`, whose fronts judge designs).
#[derive(Args)]
pub(crate) struct ObjectiveArgs {
    /// RMS SWS limit, m [default: 0.007].
    #[arg(long, value_name = "M", value_parser = number, allow_negative_numbers = true)]
    pub(crate) sws_limit: Option<f64>,
    /// Tyre-load margin K: RMS DTL at most the static wheel load / K (e.g. 3) [default: off].
    #[arg(long, value_name = "K", value_parser = number, allow_negative_numbers = true)]
    pub(crate) dtl_margin: Option<f64>,
    /// Travel budget M:N: N x RMS SWS within M metres of bump travel (e.g. 0.025:3) [default: off].
    #[arg(long, value_name = "M:N", value_parser = |s: &str| DesignBox::parse_range("travel", s), allow_hyphen_values = true)]
    pub(crate) travel: Option<(f64, f64)>,
    /// Body-bounce frequency band LO:HI, Hz (literature 0.8:1.5) [default: off].
    #[arg(long, value_name = "LO:HI", value_parser = |s: &str| DesignBox::parse_range("bounce-band", s), allow_hyphen_values = true)]
    pub(crate) bounce_band: Option<(f64, f64)>,
    /// Body damping-ratio band LO:HI (literature 0.2:0.5) [default: off].
    #[arg(long, value_name = "LO:HI", value_parser = |s: &str| DesignBox::parse_range("damping-band", s), allow_hyphen_values = true)]
    pub(crate) damping_band: Option<(f64, f64)>,
    /// Criteria no worse than the datum's: a comma list of bacc, dtl, sws [default: none].
    #[arg(long, value_name = "LIST", value_parser = no_worse)]
    pub(crate) no_worse: Option<[bool; 3]>,
}

/// `bacc,dtl` -> `[true, true, false]`.
fn no_worse(s: &str) -> Result<[bool; 3]> {
    let mut flags = [false; 3];
    for word in s.split(',').map(str::trim) {
        match ["bacc", "dtl", "sws"].iter().position(|c| *c == word) {
            Some(k) => flags[k] = true,
            None => {
                return Err(RideError::field(
                    "",
                    format!("'{word}' is not one of bacc, dtl, sws (a comma list, e.g. bacc,dtl)"),
                ))
            }
        }
    }
    Ok(flags)
}

impl ObjectiveArgs {
    /// Refuses the objectives where nothing judges designs (`why` says so): an error
    /// naming the first option given, if any.
    pub(crate) fn refuse(&self, why: &str) -> Result<()> {
        let given = [
            ("sws-limit", self.sws_limit.is_some()),
            ("dtl-margin", self.dtl_margin.is_some()),
            ("travel", self.travel.is_some()),
            ("bounce-band", self.bounce_band.is_some()),
            ("damping-band", self.damping_band.is_some()),
            ("no-worse", self.no_worse.is_some()),
        ];
        match given.iter().find(|(_, set)| *set) {
            Some((name, _)) => Err(RideError::field(*name, why.to_string())),
            None => Ok(()),
        }
    }

    /// The objectives: the defaults with these options applied, validated.
    pub(crate) fn objectives(&self) -> Result<DesignObjectives> {
        let o = DesignObjectives {
            sws_limit: self.sws_limit.or(DesignObjectives::default().sws_limit),
            dtl_margin: self.dtl_margin,
            travel: self.travel,
            bounce_band: self.bounce_band,
            damping_band: self.damping_band,
            no_worse_than_datum: self.no_worse.unwrap_or_default(),
        };
        o.validate().map_err(|e| match e {
            RideError::Field { field, reason } => RideError::field(field.replace('_', "-"), reason),
            other => other,
        })?;
        Ok(o)
    }
}

/// The adaptive loop after the plan (issue #15): `--plan ae:5 --adaptive 5` is 10 HiFi
/// runs, the last 5 placed one at a time by the infill criterion.
#[derive(Args)]
pub(crate) struct AdaptiveArgs {
    /// HiFi runs added one at a time after the plan (plan + runs <= 100).
    #[arg(long, value_name = "K", value_parser = count, allow_negative_numbers = true)]
    pub(crate) adaptive: Option<usize>,
    /// Infill criterion: ehvi-front (expected hypervolume improvement of the surrogate's
    /// predicted front x probability of meeting the SWS limit) or ehvi (of the feasible
    /// HiFi samples' front) [default: ehvi-front].
    #[arg(long, requires = "adaptive")]
    pub(crate) infill: Option<Infill>,
    /// Uncertainty estimate: model (gp-mul's own variance) or loo (leave-one-out, any
    /// surrogate) [default: model for gp-mul, else loo].
    #[arg(long, requires = "adaptive")]
    pub(crate) uncertainty: Option<UncertaintyMethod>,
    /// Candidate grid of the infill, points per axis, 2..201 [default: 41].
    #[arg(long, value_parser = count, requires = "adaptive", allow_negative_numbers = true)]
    pub(crate) candidates: Option<usize>,
    /// Smallest normalised distance of a new run to every sample, (0, 0.5] [default: 0.02].
    #[arg(long, value_name = "D", value_parser = number, allow_negative_numbers = true, requires = "adaptive")]
    pub(crate) min_distance: Option<f64>,
    /// Stop before K runs when the best candidate's EHVI x P(feasible) is below this
    /// fraction of the front's hypervolume (converged; the JSON's `stopped` says why),
    /// [0, 0.01], 0: never [default: 1e-7].
    #[arg(long, value_name = "R", value_parser = number, allow_negative_numbers = true, requires = "adaptive")]
    pub(crate) stop_below: Option<f64>,
}

impl AdaptiveArgs {
    /// The loop's options, `None` without `--adaptive`.
    pub(crate) fn options(&self) -> Option<AdaptiveOptions> {
        let d = AdaptiveOptions::default();
        self.adaptive.map(|runs| AdaptiveOptions {
            runs,
            criterion: self.infill.unwrap_or(d.criterion),
            uncertainty: self.uncertainty,
            candidates: self.candidates.unwrap_or(DEFAULT_CANDIDATES),
            min_distance: self.min_distance.unwrap_or(DEFAULT_MIN_DISTANCE),
            stop_below: self.stop_below.unwrap_or(d.stop_below),
            ..d
        })
    }
}

/// A finite number.
pub(crate) fn number(s: &str) -> Result<f64> {
    let v: f64 = s
        .trim()
        .parse()
        .map_err(|_| RideError::field("", format!("'{s}' is not a number")))?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(RideError::field("", "must be a finite number"))
    }
}

/// A whole number.
pub(crate) fn count(s: &str) -> Result<usize> {
    s.trim()
        .parse()
        .map_err(|_| RideError::field("", format!("'{s}' is not a whole number")))
}

pub(crate) fn count_u64(s: &str) -> Result<u64> {
    count(s).map(|n| n as u64)
}

/// Car (with `--ks/--cs` applied to the front) and road from the options; a car file's
/// load cases are read and checked but only map and optimize use them.
pub(crate) fn car_and_road(o: &CarRoad) -> Result<(Car, Road)> {
    car_loads_road(o).map(|(car, _, road)| (car, road))
}

/// Car (with `--ks/--cs` applied to the front), the car file's load cases and road.
/// A measured road (`--road`) is refused here: eval, map, optimize, surrogate, study,
/// simulate and report take it (each before it comes here).
pub(crate) fn car_loads_road(o: &CarRoad) -> Result<(Car, Vec<LoadCase>, Road)> {
    if o.road.is_some() {
        return Err(RideError::field(
            "road",
            "a measured road works with eval, map, optimize, surrogate, study, simulate and report (and `ridelab road FILE` describes it); this command takes --class",
        ));
    }
    car_loads_road_of(o)
}

/// [`car_loads_road`] whatever `--road` says (the caller uses it).
pub(crate) fn car_loads_road_of(o: &CarRoad) -> Result<(Car, Vec<LoadCase>, Road)> {
    let (car, loads) = match o.car.as_deref() {
        None => (Car::datum(), Vec::new()),
        Some(name) if ridelab::car::PRESETS.iter().any(|(n, _)| *n == name) => {
            (Car::preset(name)?, Vec::new())
        }
        Some(path) => {
            let text = std::fs::read_to_string(path)
                .map_err(|e| RideError::field("car", format!("cannot read '{path}': {e}")))?;
            let file = CarFile::from_json(&text)?;
            (file.car, file.load_cases)
        }
    };
    let ks = o.ks.unwrap_or(car.front.spring);
    let cs = o.cs.unwrap_or(car.front.damper);
    car.design_domain().check(ks, cs)?;
    let car = car.with_front(ks, cs)?;
    let mut road = Road::default();
    if let Some(c) = o.class {
        road.class = c;
    }
    if let Some(v) = o.speed {
        road.speed = v;
    }
    if let Some(t) = o.tracks {
        road.tracks = t;
    }
    road.validate()?;
    if !loads.is_empty() {
        // The load cases apply to the car with --ks/--cs; checked before any work.
        CaseSet::new(&car, &road, &loads, &[], Combine::Worst)?;
    }
    Ok((car, loads, road))
}

/// The study of the car, road and cases options: the car with `--ks/--cs` applied, the
/// ISO class or the measured road of `--road FILE` (shaped at `--speed`), and with
/// `cases` (map and optimize) the cases of `--cases` or the car file's load cases; the
/// box, objectives, comfort and compute the defaults (the caller sets its own). Without
/// `cases` a car file's load cases are not read on an ISO class (the command is of the
/// car as given) and refused on a measured road, naming `road`, as with `--cases`.
pub(crate) fn study_of(o: &CarRoad, cases: Option<&CasesArgs>) -> Result<StudySpec> {
    let (car, loads, iso) = car_loads_road_of(o)?;
    let Some(path) = o.road.as_deref() else {
        let set = match cases {
            Some(c) => c.set(&car, &loads, &iso)?,
            None => None,
        };
        return Ok(StudySpec {
            cases: set,
            ..StudySpec::new(car, StudyRoad::Iso(iso))
        });
    };
    // Refused before the cases file is read, naming what this command takes.
    match cases {
        Some(c) => one_scenario(c.cases.is_some() || !loads.is_empty(), false)?,
        None if !loads.is_empty() => return Err(RideError::field(
            "road",
            "a measured road is one scenario: a car file's load_cases take ISO classes (--class)",
        )),
        None => {}
    }
    let (profile, speed, tracks) = crate::road::profile_at(o, path)?;
    let road = StudyRoad::Measured(MeasuredSource::new(path, profile, speed, tracks)?);
    Ok(StudySpec::new(car, road))
}

/// `v` as pretty JSON with its `units` object ([`crate::units`]), once every number in
/// it is known to be finite (serde_json would write a NaN as `null` silently).
pub(crate) fn json<T: serde::Serialize>(v: &T) -> Result<String> {
    crate::units::json_with_units(v)
}

/// The `--svg` target, checked before any work: a file name (not a directory) in a
/// directory that exists.
pub(crate) fn svg_target(text: Option<&str>) -> Result<Option<PathBuf>> {
    let Some(text) = text else {
        return Ok(None);
    };
    if text.trim().is_empty() {
        return Err(RideError::field("svg", "needs a file name"));
    }
    let path = PathBuf::from(text);
    if path.is_dir() {
        return Err(RideError::field(
            "svg",
            format!(
                "'{text}' is a directory; give a file name (for map, a prefix such as {}/map)",
                text.trim_end_matches('/')
            ),
        ));
    }
    match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() && !dir.is_dir() => Err(RideError::field(
            "svg",
            format!("directory '{}' does not exist", dir.display()),
        )),
        _ => Ok(Some(path)),
    }
}

pub(crate) fn write_svg(path: &Path, svg: &str) -> Result<()> {
    std::fs::write(path, svg)
        .map_err(|e| RideError::field("svg", format!("cannot write '{}': {e}", path.display())))
}

/// One `warning:` line per warning about a pick ([`ridelab::optimize::trust`]).
pub(crate) fn warning_lines(w: &[Warning]) -> String {
    w.iter()
        .map(|w| format!("warning: {}\n", w.message))
        .collect()
}
