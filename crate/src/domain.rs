//! The domain of validity: the physical range of every input, in one place.
//!
//! Every car parameter, design value, design-box bound, speed, limit and load case is
//! checked here, whether it comes from the CLI, the page, a car file, a cases file, a
//! link or a session. A value outside its range is refused with the field, the value,
//! the range and why the range is what it is. The ranges span road vehicles from a
//! light quadricycle to a laden two-axle truck, so any real car fits with room to spare;
//! what lies beyond them is not a vehicle the models describe (a 1e9 kg body, a spring
//! stiffer than a steel bar), and the exact routes' numerics are tested over all of it
//! (`tests/domain.rs`).
//!
//! Messages are in SI, as the CLI and car files take them:
//! `front.spring: 1e+12 N/m is outside 1000..2e+06 N/m (spring rates of road vehicles ...)`.
//! The page shows N/m and N s/m as kN/m and kNs/m ([`page_units`]).

use crate::error::{Result, RideError};
use crate::math;

/// The unit a limit is stated in (SI, as stored).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unit {
    /// kg.
    Kilogram,
    /// m.
    Metre,
    /// N/m (spring and tyre rates).
    NewtonPerMetre,
    /// N s/m (damper rates).
    NewtonSecondPerMetre,
    /// m/s.
    MetrePerSecond,
    /// Hz.
    Hertz,
    /// A pure number.
    Ratio,
}

impl Unit {
    /// The SI symbol as messages and the CLI write it ("" for a ratio).
    fn symbol(self) -> &'static str {
        match self {
            Unit::Kilogram => "kg",
            Unit::Metre => "m",
            Unit::NewtonPerMetre => "N/m",
            Unit::NewtonSecondPerMetre => "N s/m",
            Unit::MetrePerSecond => "m/s",
            Unit::Hertz => "Hz",
            Unit::Ratio => "",
        }
    }
}

/// One quantity's physical range `min..=max` (in [`Limit::unit`]) and where it comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limit {
    /// What the quantity is, in words ("front spring rate").
    pub what: &'static str,
    /// Smallest allowed value.
    pub min: f64,
    /// Largest allowed value.
    pub max: f64,
    /// The unit of `min` and `max`.
    pub unit: Unit,
    /// Why the range is what it is.
    pub why: &'static str,
}

impl Limit {
    /// Checks `value` (in [`Limit::unit`]); the error names `field` and states the value,
    /// the range and [`Limit::why`].
    pub fn check(&self, field: &str, value: f64) -> Result<()> {
        if value.is_finite() && value >= self.min && value <= self.max {
            return Ok(());
        }
        let unit = self.unit.symbol();
        let sep = if unit.is_empty() { "" } else { " " };
        let got = if value.is_finite() {
            format!("{}{sep}{unit} is outside", num(value))
        } else {
            "must be a finite number in".to_string()
        };
        Err(RideError::field(
            field,
            format!(
                "{got} {}..{}{sep}{unit} ({})",
                num(self.min),
                num(self.max),
                self.why
            ),
        ))
    }

    /// True when `value` lies in the range.
    pub(crate) fn contains(&self, value: f64) -> bool {
        value.is_finite() && value >= self.min && value <= self.max
    }
}

/// A number as messages write it: up to 6 significant figures, plain between 1e-3 and
/// 1e6, else in exponent form (`1e+12`, `1e-320`).
pub(crate) fn num(v: f64) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    let a = v.abs();
    if a == 0.0 || (1e-3..1e6).contains(&a) {
        // Six significant figures, trailing zeros dropped.
        let decimals = if a == 0.0 {
            0
        } else {
            (5 - math::log10(a).floor() as i32).max(0) as usize
        };
        let s = format!("{v:.decimals$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    } else {
        // The shortest exact text when it has at most 6 significant figures.
        let short = format!("{v:e}");
        let s = if short.trim_start_matches('-').len() <= 12 {
            short
        } else {
            format!("{v:.5e}")
        };
        let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
        let m = m.trim_end_matches('0').trim_end_matches('.');
        let e: i32 = e.parse().unwrap_or(0);
        format!("{m}e{}{}", if e >= 0 { "+" } else { "-" }, e.abs())
    }
}

/// Sprung (body) mass, kg.
pub const SPRUNG_MASS: Limit = Limit {
    what: "sprung (body) mass",
    min: 100.0,
    max: 20_000.0,
    unit: Unit::Kilogram,
    why:
        "road vehicles: a light quadricycle's body (about 300 kg) to a laden two-axle truck (18 t)",
};

/// Dynamic index `Iyy / (M a b)`, -: the pitch inertia relative to the two-mass body.
pub const DYNAMIC_INDEX: Limit = Limit {
    what: "pitch dynamic index Iyy / (M a b)",
    min: 0.1,
    max: 5.0,
    unit: Unit::Ratio,
    why: "cars 0.8..1.2 (Gillespie 1992, ch. 5); a mass gathered between the axles gives less, long overhangs (buses) more; a 1e9 kg body with a car's inertia gives 1e-6",
};

/// Roll index `Ixx / (M (t / 2)^2)`, -, with `t` the mean track.
pub const ROLL_INDEX: Limit = Limit {
    what: "roll index Ixx / (M (t/2)^2)",
    min: 0.03,
    max: 4.0,
    unit: Unit::Ratio,
    why: "a uniform body as wide as its track gives 1/3, cars 0.4..0.9; a mass gathered on the centre line gives less, one spread beyond the wheels more",
};

/// Axle distance from the centre of gravity (`a`, `b`), m.
pub const AXLE_DISTANCE: Limit = Limit {
    what: "axle distance from the centre of gravity",
    min: 0.2,
    max: 6.0,
    unit: Unit::Metre,
    why: "wheelbases of road vehicles are 1.5..7 m",
};

/// Track width, m.
pub const TRACK: Limit = Limit {
    what: "track width",
    min: 0.8,
    max: 2.6,
    unit: Unit::Metre,
    why: "road vehicles: a quadricycle's 1 m to the 2.55 m width limit of EU and US roads",
};

/// Unsprung mass of one corner, kg.
pub const UNSPRUNG_MASS: Limit = Limit {
    what: "unsprung mass of one corner",
    min: 5.0,
    max: 1_000.0,
    unit: Unit::Kilogram,
    why: "a small car's corner (about 20 kg) to a truck's axle end",
};

/// Suspension spring rate at the wheel, N/m (the design variable Ks among them).
pub const SPRING: Limit = Limit {
    what: "suspension spring rate at the wheel",
    min: 1_000.0,
    max: 2_000_000.0,
    unit: Unit::NewtonPerMetre,
    why: "cars use 10..100 kN/m at the wheel, a truck's leaf spring up to 1000 kN/m; each corner's bounce frequency bounds it further (below)",
};

/// Suspension damper rate at the wheel, N s/m (the design variable Cs among them).
pub const DAMPER: Limit = Limit {
    what: "suspension damper rate at the wheel",
    min: 10.0,
    max: 100_000.0,
    unit: Unit::NewtonSecondPerMetre,
    why: "cars use 0.5..5 kN s/m at the wheel, trucks up to 30 kN s/m; each corner's damping ratio bounds it further (below)",
};

/// Tyre vertical stiffness, N/m.
pub const TIRE_STIFFNESS: Limit = Limit {
    what: "tyre vertical stiffness",
    min: 20_000.0,
    max: 5_000_000.0,
    unit: Unit::NewtonPerMetre,
    why: "a soft quadricycle tyre to twin truck tyres; car tyres are 150..350 kN/m",
};

/// Tyre vertical damping, N s/m.
pub const TIRE_DAMPING: Limit = Limit {
    what: "tyre vertical damping",
    min: 0.0,
    max: 5_000.0,
    unit: Unit::NewtonSecondPerMetre,
    why: "a rolling tyre's damping is small: 0..200 N s/m measured on cars",
};

/// Body-bounce frequency of a corner on its ride rate, `sqrt(Kw / ms) / (2 pi)` with
/// `Kw = k kt / (k + kt)` and `ms` the corner's share of the body, Hz.
pub(crate) const BOUNCE: Limit = Limit {
    what: "body-bounce frequency",
    min: 0.2,
    max: 5.0,
    unit: Unit::Hertz,
    why: "ride frequencies of road vehicles are 0.8..2.5 Hz (Gillespie 1992, ch. 5); at 0.2 Hz the body would sag 6 m under its own weight, 5 Hz is a kart on its tyres",
};

/// Body damping ratio of a corner, `c / (2 sqrt(k ms))` (Gillespie's ride definition), -.
pub(crate) const DAMPING_RATIO: Limit = Limit {
    what: "body damping ratio",
    min: 0.002,
    max: 20.0,
    unit: Unit::Ratio,
    why: "cars use 0.2..0.5; at 0.002 the body rings for 80 cycles, at 20 the damper is as stiff as a strut",
};

/// Unsprung mass of a corner over its share of the body, -.
pub(crate) const MASS_RATIO: Limit = Limit {
    what: "unsprung to sprung mass ratio of a corner",
    min: 0.02,
    max: 1.0,
    unit: Unit::Ratio,
    why: "cars 0.1..0.2, heavy axles up to 0.5; a wheel heavier than its share of the body is not a suspension",
};

/// Wheel-hop frequency of a corner, `sqrt((k + kt) / mu) / (2 pi)`, Hz.
pub(crate) const WHEEL_HOP: Limit = Limit {
    what: "wheel-hop frequency",
    min: 2.0,
    max: 60.0,
    unit: Unit::Hertz,
    why: "road vehicles hop at 8..15 Hz; a light wheel on a truck's tyre would hop far above the ride band",
};

/// Knee velocity of a digressive damper, m/s.
pub(crate) const KNEE_VELOCITY: Limit = Limit {
    what: "damper knee velocity",
    min: 0.005,
    max: 10.0,
    unit: Unit::MetrePerSecond,
    why: "digressive dampers change slope at 0.05..0.3 m/s; suspension speeds on roads stay below a few m/s",
};

/// Vehicle speed, m/s.
pub const SPEED: Limit = Limit {
    what: "vehicle speed",
    min: 1.0,
    max: 100.0,
    unit: Unit::MetrePerSecond,
    why: "3.6 to 360 km/h: walking pace to the fastest road cars",
};

/// RMS suspension working space limit, m.
pub(crate) const SWS_LIMIT: Limit = Limit {
    what: "RMS suspension working space limit",
    min: 1e-4,
    max: 1.0,
    unit: Unit::Metre,
    why: "0.1 mm to 1 m: road vehicles' travel is at most about 300 mm, three RMS values; a limit near 1 m leaves the SWS free",
};

/// Tyre-load margin `k` (RMS DTL at most the static wheel load / k), -.
pub(crate) const DTL_MARGIN: Limit = Limit {
    what: "tyre-load margin",
    min: 0.5,
    max: 100.0,
    unit: Unit::Ratio,
    why: "static wheel load / RMS DTL: below 1 the wheel leaves the road much of the time; 3 keeps it down 99.7 % of the time",
};

/// Available bump travel of the travel budget, m.
pub(crate) const TRAVEL: Limit = Limit {
    what: "available bump travel",
    min: 0.005,
    max: 0.5,
    unit: Unit::Metre,
    why: "5..500 mm: bump travel of road vehicles",
};

/// Sigma factor of the travel budget (`n x RMS SWS` within the travel), -.
pub(crate) const TRAVEL_SIGMAS: Limit = Limit {
    what: "travel budget's sigma factor",
    min: 0.5,
    max: 10.0,
    unit: Unit::Ratio,
    why: "how many RMS values the travel must hold: 3 is 99.7 % of the time",
};

/// A body-bounce frequency band's ends, Hz.
pub(crate) const BOUNCE_BAND: Limit = Limit {
    what: "body-bounce frequency",
    min: 0.0,
    max: 20.0,
    unit: Unit::Hertz,
    why: "ride frequencies of road vehicles are 0.5..3 Hz; the wheel hops above 8 Hz",
};

/// A damping-ratio band's ends, -.
pub(crate) const DAMPING_BAND: Limit = Limit {
    what: "body damping ratio",
    min: 0.0,
    max: 5.0,
    unit: Unit::Ratio,
    why: "cars use 0.2..0.5; above a few the body locks to the wheel",
};

/// Extra mass of a load case, kg (negative takes mass out).
pub(crate) const LOAD_MASS: Limit = Limit {
    what: "load case's extra mass",
    min: -20_000.0,
    max: 20_000.0,
    unit: Unit::Kilogram,
    why: "at most the heaviest body the models take",
};

/// A load's position ahead of (x) or above (z) the centre of gravity, m.
pub(crate) const LOAD_POSITION: Limit = Limit {
    what: "load position from the centre of gravity",
    min: -10.0,
    max: 10.0,
    unit: Unit::Metre,
    why: "inside a road vehicle: at most 10 m from its centre of gravity",
};

/// A load's lateral half-spacing, m.
pub(crate) const LOAD_SPREAD: Limit = Limit {
    what: "load's lateral half-spacing",
    min: 0.0,
    max: 1.5,
    unit: Unit::Metre,
    why: "inside a road vehicle: half of the 2.55 m width limit is 1.3 m",
};

/// Weight of a case in a weighted mean, -.
pub(crate) const CASE_WEIGHT: Limit = Limit {
    what: "case weight",
    min: 0.0,
    max: 1_000.0,
    unit: Unit::Ratio,
    why: "a relative weight: shares of time or mileage",
};

/// Every limit with the fields it checks, for the README's table.
const TABLE: [(&str, &Limit); 28] = [
    ("sprung_mass", &SPRUNG_MASS),
    ("pitch_inertia", &DYNAMIC_INDEX),
    ("roll_inertia", &ROLL_INDEX),
    ("a, b", &AXLE_DISTANCE),
    ("track_front, track_rear", &TRACK),
    ("front/rear.unsprung_mass", &UNSPRUNG_MASS),
    ("front/rear.spring, ks, design box Ks", &SPRING),
    ("front/rear.damper, cs, design box Cs", &DAMPER),
    ("front/rear.tire_stiffness", &TIRE_STIFFNESS),
    ("front/rear.tire_damping", &TIRE_DAMPING),
    ("front/rear.spring, ks (each corner)", &BOUNCE),
    ("front/rear.damper, cs (each corner)", &DAMPING_RATIO),
    ("front/rear.unsprung_mass (each corner)", &MASS_RATIO),
    ("front/rear.tire_stiffness (each corner)", &WHEEL_HOP),
    ("speed", &SPEED),
    ("sws_limit", &SWS_LIMIT),
    ("dtl_margin", &DTL_MARGIN),
    ("travel (bump travel)", &TRAVEL),
    ("travel (sigma factor)", &TRAVEL_SIGMAS),
    ("bounce_band", &BOUNCE_BAND),
    ("damping_band", &DAMPING_BAND),
    ("load_cases[i].mass", &LOAD_MASS),
    ("load_cases[i].x, z", &LOAD_POSITION),
    ("load_cases[i].y", &LOAD_SPREAD),
    ("load_cases[i].weight, operating[i].weight", &CASE_WEIGHT),
    ("bump, rebound (time domain)", &DAMPER),
    ("knee (time domain)", &KNEE_VELOCITY),
    ("operating[i].speed", &SPEED),
];

/// The domain as a Markdown table (parameter, range, reason), as the README shows it.
pub fn markdown_table() -> String {
    let mut s = String::from("| parameter | quantity | range | why |\n|---|---|---|---|\n");
    for (field, l) in TABLE {
        let unit = l.unit.symbol();
        s += &format!(
            "| `{field}` | {} | {}..{}{}{} | {} |\n",
            l.what,
            num(l.min),
            num(l.max),
            if unit.is_empty() { "" } else { " " },
            unit,
            l.why
        );
    }
    s
}

/// A message in the page's units: `N/m` values as kN/m and `N s/m` as kNs/m (the
/// page's sliders and car editor use those), the rest unchanged.
pub fn page_units(message: &str) -> String {
    let mut out = String::with_capacity(message.len());
    let tokens: Vec<&str> = message.split(' ').collect();
    let mut i = 0;
    while i < tokens.len() {
        let t = tokens[i];
        // "<number> N/m", "<number>..<number> N/m", "<number> N s/m".
        let unit_at = |k: usize| -> Option<(&str, usize)> {
            match (tokens.get(k), tokens.get(k + 1), tokens.get(k + 2)) {
                (Some(&"N"), Some(&"s/m"), _) => Some(("kNs/m", 2)),
                (Some(u), _, _) if u.starts_with("N/m") => Some(("kN/m", 1)),
                _ => None,
            }
        };
        if let Some((unit, width)) = unit_at(i + 1) {
            if let Some(scaled) = scale_numbers(t, 1e-3) {
                let rest = tokens[i + width].strip_prefix(if width == 1 { "N/m" } else { "s/m" });
                out += &scaled;
                out.push(' ');
                out += unit;
                out += rest.unwrap_or("");
                out.push(' ');
                i += 1 + width;
                continue;
            }
        }
        out += t;
        out.push(' ');
        i += 1;
    }
    out.pop();
    out
}

/// `text` (a number or `lo..hi`, optionally in brackets) with each number scaled by
/// `factor`; `None` when it is not numbers.
fn scale_numbers(text: &str, factor: f64) -> Option<String> {
    let (open, body) = match text.strip_prefix('(') {
        Some(b) => ("(", b),
        None => ("", text),
    };
    let parts: Vec<&str> = body.split("..").collect();
    let mut scaled = Vec::with_capacity(parts.len());
    for p in &parts {
        let v: f64 = p.parse().ok()?;
        scaled.push(num(v * factor));
    }
    Some(format!("{open}{}", scaled.join("..")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_as_a_user_writes_them() {
        assert_eq!(num(1000.0), "1000");
        assert_eq!(num(2e6), "2e+6");
        assert_eq!(num(1e12), "1e+12");
        assert_eq!(num(0.007), "0.007");
        assert_eq!(num(1e-320), "1e-320");
        assert_eq!(num(-20_000.0), "-20000");
        assert_eq!(num(19960.0), "19960");
        assert_eq!(num(1.0 / 3.0), "0.333333");
    }

    #[test]
    fn a_value_outside_names_the_field_value_range_and_reason() {
        let e = SPRING.check("front.spring", 1e12).unwrap_err().to_string();
        assert_eq!(
            e,
            format!(
                "front.spring: 1e+12 N/m is outside 1000..2e+6 N/m ({})",
                SPRING.why
            )
        );
        let e = SPEED.check("speed", 1e-320).unwrap_err().to_string();
        assert!(
            e.starts_with("speed: 1e-320 m/s is outside 1..100 m/s"),
            "{e}"
        );
        let e = SPRUNG_MASS
            .check("sprung_mass", f64::NAN)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("sprung_mass: must be a finite number in 100..20000 kg"),
            "{e}"
        );
        let e = DTL_MARGIN.check("dtl_margin", 0.1).unwrap_err().to_string();
        assert!(
            e.starts_with("dtl_margin: 0.1 is outside 0.5..100 ("),
            "{e}"
        );
        // The ends are inside.
        for l in TABLE.iter().map(|(_, l)| l) {
            assert!(
                l.check("x", l.min).is_ok() && l.check("x", l.max).is_ok(),
                "{}",
                l.what
            );
            assert!(l.min < l.max);
        }
    }

    #[test]
    fn page_units_show_rates_in_kilo() {
        let m = SPRING.check("front.spring", 1e12).unwrap_err().to_string();
        assert_eq!(
            page_units(&m),
            format!(
                "front.spring: 1e+9 kN/m is outside 1..2000 kN/m ({})",
                SPRING.why
            )
        );
        let m = DAMPER.check("cs", 1e9).unwrap_err().to_string();
        assert!(page_units(&m).starts_with("cs: 1e+6 kNs/m is outside 0.01..100 kNs/m ("));
        assert_eq!(page_units("speed: 200 m/s"), "speed: 200 m/s");
        assert_eq!(page_units("a (got 5 N/m)"), "a (got 0.005 kN/m)");
    }

    #[test]
    fn the_table_lists_every_limit() {
        let t = markdown_table();
        assert_eq!(t.lines().count(), TABLE.len() + 2);
        assert!(
            t.contains("| `speed` | vehicle speed | 1..100 m/s |"),
            "{t}"
        );
    }
}
