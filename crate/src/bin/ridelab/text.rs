//! Human text of the commands whose default output used to be JSON (map, surrogate,
//! study), in the page's display units: Ks in kN/m, Cs in kNs/m, BAcc in m/s^2, DTL in
//! N, SWS in mm. JSON (`--json`) and CSV (`--csv`) stay in SI with a `units` object.

use ridelab::maps::Scale;
use ridelab::road::Road;
use ridelab::road_profile::RoadScenario;
use ridelab::study::MapReport;
use ridelab::study::SurrogateReport;

/// "class B at 20 m/s, correlated tracks".
pub(crate) fn road_words(r: &Road) -> String {
    format!(
        "ISO 8608 class {:?} at {} m/s, {} tracks",
        r.class,
        r.speed,
        format!("{:?}", r.tracks).to_lowercase()
    )
}

/// A report's road (an ISO class or a measured profile) in words.
pub(crate) fn scenario_words(r: &RoadScenario) -> String {
    match r {
        RoadScenario::Iso(road) => road_words(road),
        RoadScenario::Measured(m) => format!(
            "the measured road {} at {} m/s, {} tracks (exact route; shaping-filter PSD error {:.1e} over {:.2}..{:.1} Hz)",
            m.file,
            m.speed,
            format!("{:?}", m.tracks).to_lowercase(),
            m.fit_error,
            m.band_hz[0],
            m.band_hz[1]
        ),
    }
}

/// Ks and Cs in display units.
pub(crate) fn design_words(ks: f64, cs: f64) -> String {
    format!("Ks {:.3} kN/m, Cs {:.4} kNs/m", ks / 1e3, cs / 1e3)
}

/// The map's summary: scenario, grid, datum, each field's least and most with where,
/// the feasible count.
pub(crate) fn map_text(r: &MapReport) -> String {
    let g = &r.grid;
    let mut s = format!(
        "{} map, {} on {} (computed on the {})\ngrid {} x {}: Ks {}..{} kN/m, Cs {}..{} kNs/m\n",
        r.evaluator,
        r.car,
        scenario_words(&r.road),
        format!("{:?}", r.compute).to_uppercase(),
        g.ks.n,
        g.cs.n,
        g.ks.min / 1e3,
        g.ks.max / 1e3,
        g.cs.min / 1e3,
        g.cs.max / 1e3,
    );
    let d = &r.datum;
    // "BAcc (Wk)" when the comfort slot holds the Wk-weighted value.
    let bacc = r.comfort.label();
    s += &format!(
        "datum {}: {bacc} {:.5} m/s^2, DTL {:.3} N, SWS {:.4} mm\n",
        design_words(d.ks, d.cs),
        d.criteria.bacc,
        d.criteria.dtl,
        1e3 * d.criteria.sws
    );
    let relative = r.scale == Scale::Relative;
    for (name, field, unit, factor, digits) in [
        (bacc, &r.bacc, "m/s^2", 1.0, 5),
        ("DTL", &r.dtl, "N", 1.0, 2),
        ("SWS", &r.sws, "mm", 1e3, 4),
    ] {
        let digits = if relative { 5 } else { digits };
        let (unit, factor) = if relative {
            ("x datum", 1.0)
        } else {
            (unit, factor)
        };
        let at = |i: usize| {
            let (ks, cs) = (r.ks_values[i % g.ks.n], r.cs_values[i / g.ks.n]);
            design_words(ks, cs)
        };
        let (lo, hi) = extremes(field);
        s += &format!(
            "{name:<4} {} {unit}: least {:.digits$} at {}; most {:.digits$} at {}\n",
            if relative { "relative" } else { "in" },
            factor * field[lo],
            at(lo),
            factor * field[hi],
            at(hi)
        );
    }
    let f = &r.feasibility.summary;
    s += &format!("feasible: {} of {} designs", f.feasible, f.total);
    s += &match &f.message {
        Some(m) => format!(" ({m})\n"),
        None => "\n".to_string(),
    };
    s + "--json for the fields and contours, --csv for one row per grid point, --svg PREFIX for the maps\n"
}

/// Indices of the least and the most value of a non-empty field.
fn extremes(field: &[f64]) -> (usize, usize) {
    let mut lo = 0;
    let mut hi = 0;
    for (i, v) in field.iter().enumerate() {
        if *v < field[lo] {
            lo = i;
        }
        if *v > field[hi] {
            hi = i;
        }
    }
    (lo, hi)
}

/// The surrogate's summary: what was fitted on what, and its quality on the HiFi grid.
pub(crate) fn surrogate_text(r: &SurrogateReport) -> String {
    let b = &r.design_box;
    let mut s = format!(
        "{} on plan {} ({}, {} HiFi samples), {} on {}\ndesign box Ks {}..{} kN/m, Cs {}..{} kNs/m; {} HiFi evaluations\n",
        r.surrogate,
        r.plan,
        r.plan_method,
        r.samples.len(),
        r.car,
        scenario_words(&r.road),
        b.ks_min / 1e3,
        b.ks_max / 1e3,
        b.cs_min / 1e3,
        b.cs_max / 1e3,
        r.hifi_evaluations,
    );
    s += &format!(
        "quality on the {n} x {n} HiFi validation grid:\n  criterion      R^2        RMSE   max |error|   max RTE %   mean RTE %\n",
        n = r.validation_levels
    );
    for (name, m, f) in [
        ("BAcc m/s^2", &r.metrics.bacc, 1.0),
        ("DTL N", &r.metrics.dtl, 1.0),
        ("SWS mm", &r.metrics.sws, 1e3),
    ] {
        s += &format!(
            "  {name:<11} {:>9.6} {:>11.4e} {:>13.4e} {:>11.3} {:>12.3}\n",
            m.r2,
            f * m.rmse,
            f * m.mae,
            m.rte_max,
            m.rte_mean
        );
    }
    if let Some(a) = &r.adaptive {
        s += &crate::optimize::adaptive_text(a);
    }
    s + "--json for the samples, tuning, error map and uncertainty\n"
}

/// A Markdown table as aligned plain text (the `|` and the separator row dropped);
/// other lines as they are.
pub(crate) fn plain_table(markdown: &str) -> String {
    let rows: Vec<Option<Vec<String>>> = markdown
        .lines()
        .map(|l| {
            let t = l.trim();
            (t.starts_with('|') && t.ends_with('|') && t.len() > 1).then(|| {
                t[1..t.len() - 1]
                    .split('|')
                    .map(|c| c.trim().replace('`', ""))
                    .collect()
            })
        })
        .collect();
    let is_rule = |cells: &[String]| {
        cells
            .iter()
            .all(|c| !c.is_empty() && c.chars().all(|ch| matches!(ch, '-' | ':')))
    };
    let mut widths: Vec<usize> = Vec::new();
    for cells in rows.iter().flatten().filter(|c| !is_rule(c)) {
        for (k, c) in cells.iter().enumerate() {
            let w = c.chars().count();
            match widths.get_mut(k) {
                Some(x) => *x = (*x).max(w),
                None => widths.push(w),
            }
        }
    }
    let mut out = String::new();
    for (line, cells) in markdown.lines().zip(&rows) {
        match cells {
            Some(c) if is_rule(c) => {}
            Some(c) => {
                let cols: Vec<String> = c
                    .iter()
                    .enumerate()
                    .map(|(k, v)| format!("{v:<w$}", w = widths[k]))
                    .collect();
                out += cols.join("  ").trim_end();
                out.push('\n');
            }
            None => {
                out += line.trim_start_matches('#').trim_start();
                out.push('\n');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plain_table_aligns_columns_and_drops_the_rule() {
        let t = plain_table("# Title\n\n| a | bb |\n|---|:--:|\n| ccc | `d` |\n");
        assert_eq!(t, "Title\n\na    bb\nccc  d\n");
    }

    #[test]
    fn extremes_find_least_and_most() {
        assert_eq!(extremes(&[3.0, 1.0, 4.0, 1.0]), (1, 2));
    }
}
