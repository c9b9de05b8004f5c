//! The profile file: `distance_m,elevation_m[,elevation_right_m]`, checked and put on a
//! uniform grid.
//!
//! Rules (each refusal names the column, and the row where one is at fault):
//!
//! - the first line that is not blank and not a `#` comment is the header, exactly
//!   `distance_m,elevation_m` or `distance_m,elevation_m,elevation_right_m` (case and
//!   spaces around names ignored); with the third column `elevation_m` is the left track;
//! - every data row holds one finite number per column; distance increases strictly;
//! - [`MIN_SAMPLES`]..=[`MAX_SAMPLES`] rows, at most [`MAX_BYTES`] bytes;
//! - spacing: a spacing that varies by more than [`UNIFORM_TOLERANCE`] (1 %) from the mean
//!   is resampled linearly onto the mean spacing (with a note); a gap over
//!   [`MAX_GAP_RATIO`] times the mean spacing is refused (a hole in the record), and so is a
//!   mean spacing outside [[`MIN_SPACING`], [`MAX_SPACING`]] (distances in km or mm);
//! - elevation: its roughness (wavelengths under [`ROUGHNESS_WAVELENGTH`] = 20 m, so that
//!   grades and hills do not count) must have an RMS of at most [`MAX_ROUGHNESS_RMS`]
//!   (0.5 m: more looks like millimetres) and above 1 nm (a flat line describes nothing).
//!
//! Rows are named as "row r (line l)": `r` counts data rows from 1 (the first row under
//! the header is row 1), `l` is the line of the file as an editor numbers it.

use super::welch::{segment_for_speed, segments};
use super::{BAND_HZ, LOWEST_BIN, MIN_SEGMENTS, NYQUIST_FRACTION};
use crate::error::{Result, RideError};
use std::fmt::Write as _;

/// Fewest samples (data rows) a profile may have.
pub(crate) const MIN_SAMPLES: usize = 256;
/// Most samples (data rows) a profile may have (a 100 km profile at 5 cm).
pub(crate) const MAX_SAMPLES: usize = 2_000_000;
/// Largest file accepted, bytes (128 MiB).
pub const MAX_BYTES: usize = 128 << 20;
/// A spacing that varies by more than this fraction of the mean spacing is resampled.
pub(crate) const UNIFORM_TOLERANCE: f64 = 0.01;
/// A gap larger than this many mean spacings is refused.
pub(crate) const MAX_GAP_RATIO: f64 = 10.0;
/// Smallest mean spacing accepted, m.
pub(crate) const MIN_SPACING: f64 = 0.001;
/// Largest mean spacing accepted, m (ISO 8608's band reaches 2.83 cycle/m).
pub(crate) const MAX_SPACING: f64 = 0.5;
/// Roughness is the elevation less its moving average over this length, m.
pub(crate) const ROUGHNESS_WAVELENGTH: f64 = 20.0;
/// Largest RMS roughness accepted, m (more: the file is probably in millimetres).
pub(crate) const MAX_ROUGHNESS_RMS: f64 = 0.5;
/// Smallest RMS roughness accepted, m (less: the profile is flat).
const MIN_ROUGHNESS_RMS: f64 = 1e-9;

const HEADER: [&str; 3] = ["distance_m", "elevation_m", "elevation_right_m"];
const HEADER_TEXT: &str = "distance_m,elevation_m (optionally a third column elevation_right_m)";

/// A road profile on a uniform grid: one track, or two (left and right).
#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    /// Spacing of the samples, m.
    pub spacing: f64,
    /// Distance of the first sample, m.
    pub start: f64,
    /// Elevation of the track in column `elevation_m`, m: the left track when the file
    /// has two, else both.
    pub elevation: Vec<f64>,
    /// Elevation of the right track (column `elevation_right_m`), m, if the file has it.
    pub elevation_right: Option<Vec<f64>>,
    /// What was done to the data on the way in (resampling), in words.
    pub notes: Vec<String>,
}

/// Where a value sits in the file: its data row (from 1) and its line in the file.
#[derive(Clone, Copy)]
struct At {
    row: usize,
    line: usize,
}

impl std::fmt::Display for At {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "row {} (line {})", self.row, self.line)
    }
}

impl Profile {
    /// Parses a profile file's bytes (UTF-8 text; see the module doc for the rules).
    pub fn from_csv_bytes(bytes: &[u8]) -> Result<Profile> {
        if bytes.len() > MAX_BYTES {
            return Err(RideError::field(
                "file",
                format!(
                    "{} bytes: at most {MAX_BYTES} bytes ({} MiB) are read",
                    bytes.len(),
                    MAX_BYTES >> 20
                ),
            ));
        }
        let text = std::str::from_utf8(bytes).map_err(|e| {
            RideError::field(
                "file",
                format!(
                    "not UTF-8 text (byte {} is not valid): is it a CSV file?",
                    e.valid_up_to() + 1
                ),
            )
        })?;
        Profile::from_csv(text)
    }

    /// Parses a profile file's text (see the module doc for the rules).
    pub fn from_csv(text: &str) -> Result<Profile> {
        if text.len() > MAX_BYTES {
            return Err(RideError::field(
                "file",
                format!("at most {MAX_BYTES} bytes are read"),
            ));
        }
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(i, l)| (i + 1, l.trim()))
            .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
        let Some((header_line, header)) = lines.next() else {
            return Err(RideError::field(
                "header",
                format!("the file has no data: it must start with the header {HEADER_TEXT}"),
            ));
        };
        let columns = parse_header(header, header_line)?;
        let mut cols: Vec<Vec<f64>> = vec![Vec::new(); columns];
        let mut row = 0;
        for (line, text) in lines {
            row += 1;
            let at = At { row, line };
            if row > MAX_SAMPLES {
                return Err(RideError::field(
                    "file",
                    format!(
                        "more than {MAX_SAMPLES} data rows: at most {MAX_SAMPLES} samples are read"
                    ),
                ));
            }
            let mut cells = text.split(',');
            for (c, col) in cols.iter_mut().enumerate() {
                let Some(cell) = cells.next() else {
                    return Err(RideError::field(
                        HEADER[c],
                        format!(
                            "{at}: missing (the row has {c} values, the header names {columns})"
                        ),
                    ));
                };
                col.push(number(cell.trim(), HEADER[c], at)?);
            }
            let extra = cells.count();
            if extra > 0 {
                return Err(RideError::field(
                    "file",
                    format!(
                        "{at}: {} values, but the header names {columns} columns",
                        columns + extra
                    ),
                ));
            }
            let d = &cols[0];
            if row > 1 && d[row - 1] <= d[row - 2] {
                return Err(RideError::field(
                    "distance_m",
                    format!(
                        "{at}: {} m does not increase on the row before ({} m): distance must increase strictly",
                        d[row - 1],
                        d[row - 2]
                    ),
                ));
            }
        }
        let mut it = cols.into_iter();
        let distance = it.next().unwrap_or_default();
        let elevation = it.next().unwrap_or_default();
        let right = it.next();
        Profile::from_samples(&distance, elevation, right, header_line)
    }

    /// A profile from samples at strictly increasing `distance` (m), elevations in m
    /// (`right`: the right track, if any). Resamples a non-uniform spacing onto the mean
    /// spacing (with a note) and checks the rules of the module doc. `header_line`: the
    /// file line of the header, to name rows (0 for data that came from no file).
    pub fn from_samples(
        distance: &[f64],
        elevation: Vec<f64>,
        right: Option<Vec<f64>>,
        header_line: usize,
    ) -> Result<Profile> {
        let n = distance.len();
        if n < MIN_SAMPLES {
            return Err(RideError::field(
                "file",
                format!("{n} samples: a profile needs at least {MIN_SAMPLES}"),
            ));
        }
        if n > MAX_SAMPLES {
            return Err(RideError::field(
                "file",
                format!("{n} samples: at most {MAX_SAMPLES} are read"),
            ));
        }
        if elevation.len() != n || right.as_ref().is_some_and(|r| r.len() != n) {
            return Err(RideError::field(
                "elevation_m",
                "needs one value per distance",
            ));
        }
        let at = |i: usize| At {
            row: i + 1,
            line: if header_line > 0 {
                header_line + 1 + i
            } else {
                i + 1
            },
        };
        for (i, w) in distance.windows(2).enumerate() {
            if w[1] <= w[0] || !w[0].is_finite() || !w[1].is_finite() {
                return Err(RideError::field(
                    "distance_m",
                    format!(
                        "{}: distance must be finite and increase strictly",
                        at(i + 1)
                    ),
                ));
            }
        }
        for (name, col) in [
            ("elevation_m", Some(&elevation)),
            ("elevation_right_m", right.as_ref()),
        ] {
            if let Some(i) = col.and_then(|c| c.iter().position(|v| !v.is_finite())) {
                return Err(RideError::field(
                    name,
                    format!("{}: not a finite number", at(i)),
                ));
            }
        }
        let h = (distance[n - 1] - distance[0]) / (n - 1) as f64;
        let (mut dmin, mut dmax, mut imax) = (f64::INFINITY, 0.0f64, 0);
        for (i, w) in distance.windows(2).enumerate() {
            let d = w[1] - w[0];
            dmin = dmin.min(d);
            if d > dmax {
                dmax = d;
                imax = i + 1;
            }
        }
        if dmax > MAX_GAP_RATIO * h {
            return Err(RideError::field(
                "distance_m",
                format!(
                    "{}: a gap of {dmax:.4} m, more than {MAX_GAP_RATIO} times the mean spacing \
                     {h:.4} m: the record has a hole (split the file there)",
                    at(imax)
                ),
            ));
        }
        if h < MIN_SPACING {
            return Err(RideError::field(
                "distance_m",
                format!(
                    "mean spacing {h:.3e} m is below {MIN_SPACING} m: is the distance in \
                     metres (not kilometres)?"
                ),
            ));
        }
        if h > MAX_SPACING {
            return Err(RideError::field(
                "distance_m",
                format!(
                    "mean spacing {h:.4} m is over {MAX_SPACING} m, too coarse for ISO 8608's \
                     band (to 2.83 cycle/m): is the distance in metres (not millimetres)?"
                ),
            ));
        }
        let mut notes = Vec::new();
        let (elevation, right) =
            if dmax - h > UNIFORM_TOLERANCE * h || h - dmin > UNIFORM_TOLERANCE * h {
                notes.push(format!(
                    "distance_m: the spacing varies from {dmin:.4} to {dmax:.4} m, more than \
                 {:.0} % from the mean {h:.4} m: resampled linearly onto the mean spacing",
                    UNIFORM_TOLERANCE * 100.0
                ));
                (
                    resample(distance, &elevation, h),
                    right.map(|r| resample(distance, &r, h)),
                )
            } else {
                (elevation, right)
            };
        let p = Profile {
            spacing: h,
            start: distance[0],
            elevation,
            elevation_right: right,
            notes,
        };
        p.check_elevations()?;
        Ok(p)
    }

    /// A profile already on a uniform grid (`spacing` m, first sample at `start` m),
    /// checked like a file.
    pub(crate) fn uniform(
        spacing: f64,
        start: f64,
        elevation: Vec<f64>,
        right: Option<Vec<f64>>,
    ) -> Result<Profile> {
        if !(spacing.is_finite() && (MIN_SPACING..=MAX_SPACING).contains(&spacing)) {
            return Err(RideError::field(
                "spacing",
                format!("must be in [{MIN_SPACING}, {MAX_SPACING}] m"),
            ));
        }
        if !start.is_finite() {
            return Err(RideError::field("start", "must be finite (m)"));
        }
        let n = elevation.len();
        let distance: Vec<f64> = (0..n).map(|i| start + i as f64 * spacing).collect();
        let mut p = Profile::from_samples(&distance, elevation, right, 0)?;
        p.spacing = spacing;
        Ok(p)
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.elevation.len()
    }

    /// Always false: a profile holds at least [`MIN_SAMPLES`] samples.
    pub fn is_empty(&self) -> bool {
        self.elevation.is_empty()
    }

    /// Length covered, `(N - 1) dx`, m.
    pub(crate) fn length(&self) -> f64 {
        (self.len() - 1) as f64 * self.spacing
    }

    /// Number of tracks (1 or 2).
    pub fn tracks(&self) -> usize {
        1 + usize::from(self.elevation_right.is_some())
    }

    /// The right track (the only track when the file has one), m.
    pub(crate) fn right(&self) -> &[f64] {
        self.elevation_right.as_deref().unwrap_or(&self.elevation)
    }

    /// The left track (column `elevation_m`), m.
    pub(crate) fn left(&self) -> &[f64] {
        &self.elevation
    }

    /// Welch segment length of [`super::describe`], samples.
    pub(crate) fn segment_samples(&self) -> usize {
        super::welch::segment_length(self.len())
    }

    /// Spatial frequency band [`super::describe`] resolves, cycle/m: from [`LOWEST_BIN`]
    /// Welch bins to [`NYQUIST_FRACTION`] of the Nyquist frequency.
    pub(crate) fn resolved_band(&self) -> [f64; 2] {
        let dn = 1.0 / (self.segment_samples() as f64 * self.spacing);
        [LOWEST_BIN * dn, NYQUIST_FRACTION * 0.5 / self.spacing]
    }

    /// Welch segment length of the road at `speed` (m/s), samples: as long as the band
    /// [`BAND_HZ`] needs down to its lower edge, `LOWEST_BIN v / (f_lo dx)` rounded up to a
    /// fast FFT length.
    pub(crate) fn segment_at(&self, speed: f64) -> usize {
        segment_for_speed(speed, self.spacing)
    }

    /// Length this profile must have at `speed` (m/s), m: [`MIN_SEGMENTS`] Welch segments
    /// of [`Profile::segment_at`] with 50 % overlap, `(MIN_SEGMENTS + 1) / 2` segments:
    /// about `4.5 LOWEST_BIN v / f_lo = 45 v` (900 m at 20 m/s).
    fn required_length(&self, speed: f64) -> f64 {
        let seg = self.segment_at(speed) as f64;
        (seg * (MIN_SEGMENTS + 1) as f64 / 2.0).ceil() * self.spacing
    }

    /// Refuses a profile too short for the band [`BAND_HZ`] at `speed` (m/s), saying how
    /// long it must be ([`Profile::required_length`]).
    pub(crate) fn check_length(&self, speed: f64) -> Result<()> {
        if !(speed.is_finite() && speed > 0.0 && speed <= 100.0) {
            return Err(RideError::field("speed", "must be in (0, 100] m/s"));
        }
        let seg = self.segment_at(speed);
        if segments(self.len(), seg) < MIN_SEGMENTS {
            return Err(RideError::field(
                "distance_m",
                format!(
                    "the profile is {:.0} m long, too short for {speed} m/s: the band down to \
                     {} Hz needs Welch segments of {:.0} m and {MIN_SEGMENTS} of them (50 % \
                     overlap), at least {:.0} m",
                    self.length(),
                    BAND_HZ[0],
                    seg as f64 * self.spacing,
                    self.required_length(speed)
                ),
            ));
        }
        Ok(())
    }

    /// The profile as a CSV file (distance with `decimals_x`, elevations with
    /// `decimals_z` decimals), as [`Profile::from_csv`] reads it.
    pub fn to_csv(&self, decimals_x: usize, decimals_z: usize) -> String {
        let mut s = String::with_capacity(self.len() * 32);
        s.push_str(if self.elevation_right.is_some() {
            "distance_m,elevation_m,elevation_right_m\n"
        } else {
            "distance_m,elevation_m\n"
        });
        for i in 0..self.len() {
            let x = self.start + i as f64 * self.spacing;
            let _ = write!(s, "{x:.decimals_x$},{:.decimals_z$}", self.elevation[i]);
            if let Some(r) = &self.elevation_right {
                let _ = write!(s, ",{:.decimals_z$}", r[i]);
            }
            s.push('\n');
        }
        s
    }

    /// Checks each track's roughness RMS (see the module doc).
    fn check_elevations(&self) -> Result<()> {
        let tracks = [
            ("elevation_m", Some(&self.elevation)),
            ("elevation_right_m", self.elevation_right.as_ref()),
        ];
        for (name, track) in tracks {
            let Some(z) = track else { continue };
            let rms = roughness_rms(z, self.spacing);
            if rms > MAX_ROUGHNESS_RMS {
                return Err(RideError::field(
                    name,
                    format!(
                        "the RMS roughness (wavelengths under {ROUGHNESS_WAVELENGTH} m) is \
                         {rms:.3} m, over {MAX_ROUGHNESS_RMS} m: the elevations look like \
                         millimetres; give them in metres"
                    ),
                ));
            }
            if rms < MIN_ROUGHNESS_RMS {
                return Err(RideError::field(
                    name,
                    "the profile is flat (RMS roughness under 1 nm): nothing to describe",
                ));
            }
        }
        Ok(())
    }
}

/// Parses the header line, returning the number of columns (2 or 3).
fn parse_header(header: &str, line: usize) -> Result<usize> {
    let cells: Vec<String> = header
        .split(',')
        .map(|c| c.trim().trim_matches('"').to_ascii_lowercase())
        .collect();
    if cells.iter().all(|c| c.parse::<f64>().is_ok()) {
        return Err(RideError::field(
            "header",
            format!(
                "line {line} holds numbers, not the header: the file must start with {HEADER_TEXT}"
            ),
        ));
    }
    for (i, c) in cells.iter().enumerate() {
        if i >= HEADER.len() {
            return Err(RideError::field(
                "header",
                format!(
                    "line {line}: column {} '{c}' is not expected; the header is {HEADER_TEXT}",
                    i + 1
                ),
            ));
        }
        if c != HEADER[i] {
            return Err(RideError::field(
                HEADER[i],
                format!(
                    "line {line}: header column {} is '{c}' where '{}' is expected; the header is {HEADER_TEXT}",
                    i + 1,
                    HEADER[i]
                ),
            ));
        }
    }
    if cells.len() < 2 {
        return Err(RideError::field(
            "elevation_m",
            format!("line {line}: missing from the header; the header is {HEADER_TEXT}"),
        ));
    }
    Ok(cells.len())
}

/// One cell as a finite number, or a refusal naming the column and row.
fn number(cell: &str, column: &str, at: At) -> Result<f64> {
    // The cell as the message shows it, made only for a message (a file has 10^5 cells).
    let shown = || cell.chars().take(24).collect::<String>();
    if cell.is_empty() {
        return Err(RideError::field(column, format!("{at}: empty")));
    }
    match cell.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(RideError::field(
            column,
            format!("{at}: '{}' is not a finite number", shown()),
        )),
        Err(_) => Err(RideError::field(
            column,
            format!("{at}: '{}' is not a number", shown()),
        )),
    }
}

/// Linear interpolation of `z(x)` onto `x0 + k h`, `k = 0..N-1`.
fn resample(x: &[f64], z: &[f64], h: f64) -> Vec<f64> {
    let n = x.len();
    let mut out = Vec::with_capacity(n);
    let mut j = 0;
    for k in 0..n {
        let xi = if k == n - 1 {
            x[n - 1]
        } else {
            x[0] + k as f64 * h
        };
        while j + 2 < n && x[j + 1] < xi {
            j += 1;
        }
        let t = ((xi - x[j]) / (x[j + 1] - x[j])).clamp(0.0, 1.0);
        out.push(z[j] + t * (z[j + 1] - z[j]));
    }
    out
}

/// RMS of `z` less its centred moving average over [`ROUGHNESS_WAVELENGTH`] (a symmetric
/// window, shorter at the ends), m: the roughness, without grades and hills.
fn roughness_rms(z: &[f64], h: f64) -> f64 {
    let n = z.len();
    let half = ((0.5 * ROUGHNESS_WAVELENGTH / h).round() as usize).clamp(1, n / 2);
    // Prefix sums of z minus its mean, for O(1) window means (kept small for accuracy).
    let mean = z.iter().sum::<f64>() / n as f64;
    let mut prefix = Vec::with_capacity(n + 1);
    prefix.push(0.0);
    let mut s = 0.0;
    for v in z {
        s += v - mean;
        prefix.push(s);
    }
    let mut sum2 = 0.0;
    for i in 0..n {
        // A symmetric window (shorter at the ends) takes out a linear trend exactly.
        let k = half.min(i).min(n - 1 - i);
        let (lo, hi) = (i - k, i + k + 1);
        let avg = (prefix[hi] - prefix[lo]) / (hi - lo) as f64;
        let r = z[i] - mean - avg;
        sum2 += r * r;
    }
    (sum2 / n as f64).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// A valid file body: `n` rows at 5 cm, a few-mm sinusoidal roughness.
    fn good(n: usize, right: bool) -> String {
        let mut s = String::from(if right {
            "distance_m,elevation_m,elevation_right_m\n"
        } else {
            "distance_m,elevation_m\n"
        });
        for i in 0..n {
            let x = i as f64 * 0.05;
            let z = 0.003 * (x * 1.3).sin() + 0.001 * (x * 7.1).cos();
            if right {
                s += &format!("{x},{z},{}\n", -z);
            } else {
                s += &format!("{x},{z}\n");
            }
        }
        s
    }

    fn refusal(text: &str) -> (String, String) {
        match Profile::from_csv(text) {
            Err(RideError::Field { field, reason }) => (field, reason),
            other => panic!("expected a field error, got {other:?}"),
        }
    }

    #[test]
    fn a_good_file_parses_with_one_or_two_tracks() {
        let p = Profile::from_csv(&good(400, false)).unwrap();
        assert_eq!(p.len(), 400);
        assert!((p.spacing - 0.05).abs() < 1e-12);
        assert_eq!(p.tracks(), 1);
        assert!(p.notes.is_empty());
        let text = format!("# measured 2024\n\u{feff}{}", good(300, true)).replace('\n', "\r\n");
        let q = Profile::from_csv(&text.replacen('\u{feff}', "", 1)).unwrap();
        assert_eq!(q.tracks(), 2);
        assert_eq!(q.right()[5], -q.left()[5]);
        // Round trip through the writer.
        let r = Profile::from_csv(&q.to_csv(3, 9)).unwrap();
        assert_eq!(r.len(), q.len());
        assert!((r.right()[7] - q.right()[7]).abs() < 1e-9);
    }

    #[test]
    fn bad_headers_name_the_column() {
        let body = good(300, false);
        let (f, r) = refusal(&body.replacen("distance_m", "dist", 1));
        assert_eq!(f, "distance_m");
        assert!(r.contains("line 1") && r.contains("'dist'"), "{r}");
        let (f, _) = refusal(&body.replacen("elevation_m", "z_mm", 1));
        assert_eq!(f, "elevation_m");
        let (f, r) = refusal(&body.replacen("distance_m,elevation_m", "distance_m", 1));
        assert_eq!(f, "elevation_m", "{r}");
        let (f, r) = refusal(&body.replacen("elevation_m", "elevation_m,elevation_right_m,x", 1));
        assert_eq!(f, "header");
        assert!(r.contains("column 4"), "{r}");
        let (f, r) = refusal(&body.replacen("distance_m,elevation_m\n", "", 1));
        assert_eq!(f, "header");
        assert!(r.contains("numbers"), "{r}");
        let (f, _) = refusal("");
        assert_eq!(f, "header");
        let (f, _) = refusal("# only a comment\n\n");
        assert_eq!(f, "header");
    }

    #[test]
    fn bad_rows_name_the_column_and_the_row() {
        let body = good(300, true);
        let lines: Vec<&str> = body.lines().collect();
        let with = |line_index: usize, text: &str| {
            let mut l = lines.clone();
            l[line_index] = text;
            l.join("\n")
        };
        // Line 11 of the file is data row 10.
        let (f, r) = refusal(&with(10, "0.45,abc,0.001"));
        assert_eq!(f, "elevation_m");
        assert!(
            r.starts_with("row 10 (line 11)") && r.contains("'abc'"),
            "{r}"
        );
        let (f, r) = refusal(&with(10, "0.45,0.001,NaN"));
        assert_eq!(f, "elevation_right_m");
        assert!(r.contains("not a finite number"), "{r}");
        let (f, r) = refusal(&with(10, "0.45,inf,0.0"));
        assert_eq!(f, "elevation_m", "{r}");
        let (f, r) = refusal(&with(10, "0.40,0.0,0.0"));
        assert_eq!(f, "distance_m");
        assert!(
            r.starts_with("row 10 (line 11)") && r.contains("increase"),
            "{r}"
        );
        let (f, r) = refusal(&with(10, "0.45,0.0"));
        assert_eq!(f, "elevation_right_m");
        assert!(r.contains("missing"), "{r}");
        let (f, r) = refusal(&with(10, "0.45,0.0,0.0,0.0"));
        assert_eq!(f, "file");
        assert!(r.contains("row 10"), "{r}");
        let (f, r) = refusal(&with(10, ",0.0,0.0"));
        assert_eq!(f, "distance_m");
        assert!(r.contains("empty"), "{r}");
        // A comment line between rows shifts the line number, not the row number.
        let mut l = lines.clone();
        l.insert(3, "# a comment");
        l[11] = "0.45,x,0";
        let (_, r) = refusal(&l.join("\n"));
        assert!(r.starts_with("row 10 (line 12)"), "{r}");
    }

    #[test]
    fn too_few_millimetres_flat_coarse_and_holes_are_refused() {
        let (f, r) = refusal(&good(100, false));
        assert_eq!(f, "file");
        assert!(r.contains("100 samples") && r.contains("256"), "{r}");
        // Millimetres: the same roughness times 1000, on a 3 % grade (grades do not count).
        let mut mm = String::from("distance_m,elevation_m\n");
        for i in 0..2000 {
            let x = i as f64 * 0.05;
            mm += &format!("{x},{}\n", 0.03 * x + 1000.0 * 0.003 * (x * 1.3).sin());
        }
        let (f, r) = refusal(&mm);
        assert_eq!(f, "elevation_m");
        assert!(r.contains("millimetres") && r.contains("0.5 m"), "{r}");
        // The same grade with metre roughness passes.
        let mut ok = String::from("distance_m,elevation_m\n");
        for i in 0..2000 {
            let x = i as f64 * 0.05;
            ok += &format!("{x},{}\n", 0.03 * x + 0.003 * (x * 1.3).sin());
        }
        assert!(Profile::from_csv(&ok).is_ok());
        let mut flat = String::from("distance_m,elevation_m\n");
        for i in 0..300 {
            flat += &format!("{},1.5\n", i as f64 * 0.05);
        }
        assert!(refusal(&flat).1.contains("flat"));
        let mut c = String::from("distance_m,elevation_m\n");
        for i in 0..300 {
            c += &format!("{},0.00{}\n", i as f64 * 2.0, i % 7);
        }
        let (f, r) = refusal(&c);
        assert_eq!(f, "distance_m");
        assert!(r.contains("too coarse"), "{r}");
        let mut hole = String::from("distance_m,elevation_m\n");
        for i in 0..300 {
            let x = if i < 150 {
                i as f64 * 0.05
            } else {
                10.0 + i as f64 * 0.05
            };
            hole += &format!("{x},{}\n", 0.001 * (x * 3.0).sin());
        }
        let (f, r) = refusal(&hole);
        assert_eq!(f, "distance_m");
        assert!(
            r.starts_with("row 151 (line 152)") && r.contains("hole"),
            "{r}"
        );
    }

    #[test]
    fn a_varying_spacing_is_resampled_with_a_note() {
        let mut s = String::from("distance_m,elevation_m\n");
        let mut x = 0.0f64;
        for i in 0..1000 {
            s += &format!("{x},{}\n", 0.002 * (x * 0.9).sin());
            x += if i % 2 == 0 { 0.045 } else { 0.055 };
        }
        let p = Profile::from_csv(&s).unwrap();
        assert_eq!(p.notes.len(), 1);
        assert!(p.notes[0].contains("resampled"), "{}", p.notes[0]);
        assert!((p.spacing - 0.05).abs() < 1e-3);
        // Linear resampling of a smooth function is close to the function.
        for i in [10, 500, 998] {
            let xi = i as f64 * p.spacing;
            assert!((p.elevation[i] - 0.002 * (xi * 0.9).sin()).abs() < 1e-6);
        }
        // Within 1 % no resampling.
        let mut t = String::from("distance_m,elevation_m\n");
        for i in 0..400 {
            let x = i as f64 * 0.05 + if i % 2 == 0 { 0.0002 } else { 0.0 };
            t += &format!("{x},{}\n", 0.002 * (x * 0.9).sin());
        }
        assert!(Profile::from_csv(&t).unwrap().notes.is_empty());
    }

    #[test]
    fn the_length_check_says_how_long() {
        let p = Profile::from_csv(&good(4000, false)).unwrap(); // 200 m
        let e = p.check_length(20.0).unwrap_err().to_string();
        assert!(
            e.starts_with("distance_m") && e.contains("at least 900 m"),
            "{e}"
        );
        assert_eq!(p.required_length(20.0), 900.0);
        // A profile of the stated length passes.
        let n = (p.required_length(20.0) / 0.05) as usize + 2;
        let long: Vec<f64> = (0..n).map(|i| 0.002 * (i as f64 * 0.05).sin()).collect();
        let q = Profile::uniform(0.05, 0.0, long, None).unwrap();
        q.check_length(20.0).unwrap();
        assert!(q.check_length(0.0).is_err());
    }

    /// Random bytes, random CSV-like text and random edits of a good file never panic:
    /// each is parsed or refused with a named field.
    #[test]
    fn fuzzed_input_never_panics() {
        let mut rng = ChaCha8Rng::seed_from_u64(31);
        let base = good(300, true);
        let alphabet = b"0123456789.,-+eE\n\r #naif\xff\xfe";
        for i in 0..600 {
            let bytes: Vec<u8> = match i % 3 {
                0 => (0..rng.random_range(0..400))
                    .map(|_| rng.random())
                    .collect(),
                1 => {
                    let mut b = b"distance_m,elevation_m\n".to_vec();
                    b.extend(
                        (0..rng.random_range(0..3000))
                            .map(|_| alphabet[rng.random_range(0..alphabet.len())]),
                    );
                    b
                }
                _ => {
                    let mut b = base.as_bytes().to_vec();
                    for _ in 0..rng.random_range(1..5) {
                        let k = rng.random_range(0..b.len());
                        b[k] = alphabet[rng.random_range(0..alphabet.len())];
                    }
                    b
                }
            };
            match Profile::from_csv_bytes(&bytes) {
                Ok(p) => assert!(p.len() >= MIN_SAMPLES),
                Err(RideError::Field { field, reason }) => {
                    assert!(!field.is_empty() && !reason.is_empty())
                }
                Err(e) => panic!("unexpected error kind {e:?}"),
            }
        }
    }
}
