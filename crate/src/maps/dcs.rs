//! Design criteria space (DCS): BAcc, DTL and SWS on a Ks x Cs grid, for any evaluator
//! (LoFi, HiFi, surrogate), absolute or relative to the datum car.
//!
//! Points are evaluated in parallel where the platform has threads: rows of the grid are
//! split over [`std::thread::available_parallelism`] scoped threads on native targets; on
//! wasm32 the loop runs on the calling thread. Either way the evaluator must be `Sync`, and
//! every value is what `evaluator.evaluate(ks, cs)` returns at that point, bit for bit.

use super::grid::Grid;
use crate::error::{Result, RideError};
use crate::evaluate::{Criteria, Evaluator, CRITERIA_NAMES};
use serde::{Deserialize, Serialize};

/// Absolute criteria, or ratios to the datum car's criteria.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Scale {
    /// SI values: m/s^2, N, m.
    #[default]
    Absolute,
    /// `value / datum value`, dimensionless (1 at the datum design).
    Relative,
}

/// The datum design on a map and its criteria (always absolute, SI).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DatumPoint {
    /// Datum front spring rate, N/m.
    pub ks: f64,
    /// Datum front damper rate, N s/m.
    pub cs: f64,
    /// The evaluator's criteria at `(ks, cs)`.
    pub criteria: Criteria,
}

/// The three criteria on a grid. Fields are row-major with Cs rows and Ks columns:
/// the value at Ks index `i`, Cs index `j` is at `j * grid.ks.n + i` (see [`Grid::index`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Dcs {
    /// Name of the evaluator that made the map.
    pub evaluator: String,
    /// The grid.
    pub grid: Grid,
    /// Absolute or relative to the datum.
    pub scale: Scale,
    /// The datum design and its absolute criteria.
    pub datum: DatumPoint,
    /// RMS body acceleration, m/s^2 (or ratio to the datum).
    pub bacc: Vec<f64>,
    /// RMS dynamic tyre load, N (or ratio to the datum).
    pub dtl: Vec<f64>,
    /// RMS suspension working space, m (or ratio to the datum).
    pub sws: Vec<f64>,
}

impl Dcs {
    /// Maps `evaluator` over `grid`; `datum = (ks, cs)` is the datum design, evaluated too
    /// and recorded. With [`Scale::Relative`] every value is divided by the datum's.
    /// Uses [`default_threads`] threads.
    pub fn compute<E: Evaluator + Sync + ?Sized>(
        evaluator: &E,
        grid: &Grid,
        datum: (f64, f64),
        scale: Scale,
    ) -> Result<Dcs> {
        Dcs::compute_with_threads(evaluator, grid, datum, scale, default_threads())
    }

    /// As [`Dcs::compute`] on at most `threads` threads (1 runs on the calling thread;
    /// wasm32 always does).
    pub fn compute_with_threads<E: Evaluator + Sync + ?Sized>(
        evaluator: &E,
        grid: &Grid,
        datum: (f64, f64),
        scale: Scale,
        threads: usize,
    ) -> Result<Dcs> {
        grid.validate()?;
        let (dks, dcs) = datum;
        let datum_criteria = evaluator.evaluate(dks, dcs).map_err(|e| {
            at_point(
                e,
                &format!("datum point (ks = {dks} N/m, cs = {dcs} N s/m)"),
            )
        })?;
        let values = evaluate_grid(evaluator, grid, threads)?;
        let mut map = Dcs {
            evaluator: evaluator.name(),
            grid: *grid,
            scale: Scale::Absolute,
            datum: DatumPoint {
                ks: dks,
                cs: dcs,
                criteria: datum_criteria,
            },
            bacc: values.iter().map(|c| c.bacc).collect(),
            dtl: values.iter().map(|c| c.dtl).collect(),
            sws: values.iter().map(|c| c.sws).collect(),
        };
        if scale == Scale::Relative {
            map = map.to_scale(Scale::Relative);
        }
        Ok(map)
    }

    /// The field of criterion `k` in the order of [`CRITERIA_NAMES`] (0 bacc, 1 dtl, 2 sws).
    ///
    /// # Panics
    /// If `k > 2`.
    pub fn field(&self, k: usize) -> &[f64] {
        match k {
            0 => &self.bacc,
            1 => &self.dtl,
            2 => &self.sws,
            _ => panic!("criterion index {k} is not 0..3 ({CRITERIA_NAMES:?})"),
        }
    }

    /// The three values at Ks column `i`, Cs row `j`, in the map's scale.
    pub fn criteria_at(&self, i: usize, j: usize) -> Criteria {
        let k = self.grid.index(i, j);
        Criteria {
            bacc: self.bacc[k],
            dtl: self.dtl[k],
            sws: self.sws[k],
        }
    }

    /// The map in `scale`: absolute to relative divides each value by the datum's,
    /// relative to absolute multiplies back (exact up to one rounding).
    pub(crate) fn to_scale(&self, scale: Scale) -> Dcs {
        let d = self.datum.criteria.to_array();
        let convert = |v: &[f64], dk: f64| -> Vec<f64> {
            match (self.scale, scale) {
                (Scale::Absolute, Scale::Relative) => v.iter().map(|x| x / dk).collect(),
                (Scale::Relative, Scale::Absolute) => v.iter().map(|x| x * dk).collect(),
                _ => v.to_vec(),
            }
        };
        Dcs {
            evaluator: self.evaluator.clone(),
            grid: self.grid,
            scale,
            datum: self.datum,
            bacc: convert(&self.bacc, d[0]),
            dtl: convert(&self.dtl, d[1]),
            sws: convert(&self.sws, d[2]),
        }
    }
}

/// Threads a map uses by default: [`std::thread::available_parallelism`] on native
/// targets (1 if unknown), 1 on wasm32.
pub fn default_threads() -> usize {
    #[cfg(not(target_arch = "wasm32"))]
    {
        std::thread::available_parallelism()
            .map(|n| n.get())
            .unwrap_or(1)
    }
    #[cfg(target_arch = "wasm32")]
    {
        1
    }
}

/// The criteria at every grid point, row-major (Cs rows, Ks columns), on at most
/// `threads` threads. The first failing point (in row-major order) makes the whole call
/// fail with a message naming that point.
pub fn evaluate_grid<E: Evaluator + Sync + ?Sized>(
    evaluator: &E,
    grid: &Grid,
    threads: usize,
) -> Result<Vec<Criteria>> {
    let zero = Criteria {
        bacc: 0.0,
        dtl: 0.0,
        sws: 0.0,
    };
    map_grid(grid, threads, zero, |ks, cs| evaluator.evaluate(ks, cs))
}

/// `f(ks, cs)` at every grid point, row-major (Cs rows, Ks columns), on at most `threads`
/// threads, as [`evaluate_grid`] (which is this with an evaluator): the first failing
/// point in row-major order makes the whole call fail with a message naming that point.
/// `fill` is the initial value of each slot. For several values a point, e.g. every road
/// of [`crate::analysis::HiFiRoads`].
pub(crate) fn map_grid<T, F>(grid: &Grid, threads: usize, fill: T, f: F) -> Result<Vec<T>>
where
    T: Clone + Send,
    F: Fn(f64, f64) -> Result<T> + Sync,
{
    grid.validate()?;
    let ks = grid.ks.values();
    let cs = grid.cs.values();
    let mut out = vec![fill; grid.len()];
    let rows_of =
        |first_row: usize, chunk: &mut [T]| -> std::result::Result<(), (usize, RideError)> {
            for (r, row) in chunk.chunks_mut(ks.len()).enumerate() {
                let j = first_row + r;
                for (i, slot) in row.iter_mut().enumerate() {
                    *slot = f(ks[i], cs[j]).map_err(|e| (j * ks.len() + i, e))?;
                }
            }
            Ok(())
        };
    let threads = threads.clamp(1, cs.len());
    let failure = if threads == 1 {
        rows_of(0, &mut out).err()
    } else {
        run_threads(&mut out, ks.len(), threads, &rows_of)
    };
    match failure {
        None => Ok(out),
        Some((k, e)) => {
            let (i, j) = grid.indices(k);
            Err(at_point(
                e,
                &format!(
                    "map point ks = {} N/m, cs = {} N s/m (column {i}, row {j})",
                    ks[i], cs[j]
                ),
            ))
        }
    }
}

/// Below this estimated time for the rows after the first, a map stays on the calling
/// thread: spawning threads costs more than it saves (a LoFi 101 x 101 map takes about
/// 0.35 ms in all).
#[cfg(not(target_arch = "wasm32"))]
const PARALLEL_MIN_SECONDS: f64 = 1e-3;

/// Runs the first row on the calling thread and times it. When the other rows would take
/// under [`PARALLEL_MIN_SECONDS`] they follow on the calling thread; otherwise the calling
/// thread and `threads - 1` scoped threads each take the next unclaimed row (rows are
/// claimed in order, so a slow or busy core holds back at most one row). Returns the
/// failure with the lowest flat index, if any; after a failure no later row is started.
#[cfg(not(target_arch = "wasm32"))]
fn run_threads<T: Send, F>(
    out: &mut [T],
    n_ks: usize,
    threads: usize,
    rows_of: &F,
) -> Option<(usize, RideError)>
where
    F: Fn(usize, &mut [T]) -> std::result::Result<(), (usize, RideError)> + Sync,
{
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::sync::Mutex;
    let (first, rest) = out.split_at_mut(n_ks);
    let start = std::time::Instant::now();
    if let Err(e) = rows_of(0, first) {
        return Some(e);
    }
    let estimate = start.elapsed().as_secs_f64() * (rest.len() / n_ks) as f64;
    if estimate < PARALLEL_MIN_SECONDS {
        return rows_of(1, rest).err();
    }
    let rows = Mutex::new(rest.chunks_mut(n_ks).enumerate());
    let failed_row = AtomicUsize::new(usize::MAX);
    let work = || loop {
        // The guard is dropped at the end of this statement, before the evaluator runs.
        let next = rows.lock().unwrap_or_else(|p| p.into_inner()).next();
        let (r, row) = next?;
        let j = r + 1;
        if j > failed_row.load(Ordering::Relaxed) {
            return None;
        }
        if let Err(e) = rows_of(j, row) {
            failed_row.fetch_min(j, Ordering::Relaxed);
            return Some(e);
        }
    };
    std::thread::scope(|s| {
        let handles: Vec<_> = (1..threads).map(|_| s.spawn(work)).collect();
        let mine = work();
        handles
            .into_iter()
            .filter_map(|h| match h.join() {
                Ok(r) => r,
                // A panicking evaluator: re-raise it on the calling thread.
                Err(p) => std::panic::resume_unwind(p),
            })
            .chain(mine)
            .min_by_key(|(k, _)| *k)
    })
}

/// wasm32 has no threads: the rows run on the calling thread.
#[cfg(target_arch = "wasm32")]
fn run_threads<T, F>(
    out: &mut [T],
    _n_ks: usize,
    _threads: usize,
    rows_of: &F,
) -> Option<(usize, RideError)>
where
    F: Fn(usize, &mut [T]) -> std::result::Result<(), (usize, RideError)> + Sync,
{
    rows_of(0, out).err()
}

/// Adds `where` to an evaluator's error, keeping its kind (a field error stays one).
fn at_point(e: RideError, place: &str) -> RideError {
    match e {
        RideError::Field { field, reason } => RideError::Field {
            field,
            reason: format!("{reason} at {place}"),
        },
        RideError::Numerical(m) => RideError::Numerical(format!("{place}: {m}")),
        other => RideError::Numerical(format!("{place}: {other}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::{HiFi, LoFi};
    use crate::car::Car;
    use crate::road::{Road, RoadClass};

    fn lofi() -> LoFi {
        LoFi {
            car: Car::datum(),
            road: Road::default(),
        }
    }

    fn datum_point(car: &Car) -> (f64, f64) {
        (car.front.spring, car.front.damper)
    }

    fn assert_matches_points<E: Evaluator + Sync + ?Sized>(e: &E, map: &Dcs) -> f64 {
        let mut worst = 0.0f64;
        for j in 0..map.grid.cs.n {
            for i in 0..map.grid.ks.n {
                let (ks, cs) = map.grid.point(i, j);
                let p = e.evaluate(ks, cs).unwrap().to_array();
                let m = map.criteria_at(i, j).to_array();
                for k in 0..3 {
                    worst = worst.max(((m[k] - p[k]) / p[k]).abs());
                    assert!(
                        m[k] == p[k] || ((m[k] - p[k]) / p[k]).abs() <= 1e-15,
                        "{} at ({i}, {j}): map {} point {}",
                        CRITERIA_NAMES[k],
                        m[k],
                        p[k]
                    );
                }
            }
        }
        worst
    }

    #[test]
    fn lofi_map_equals_point_evaluations() {
        let e = lofi();
        let grid = Grid::parse("10000:40000:13", "500:4000:11").unwrap();
        for threads in [1, 2, 3, 64] {
            let map =
                Dcs::compute_with_threads(&e, &grid, datum_point(&e.car), Scale::Absolute, threads)
                    .unwrap();
            assert_eq!(assert_matches_points(&e, &map), 0.0, "threads {threads}");
            assert_eq!(map.bacc.len(), 13 * 11);
            assert_eq!(map.evaluator, "quarter");
        }
        // The dyn interface gives the same map.
        let d: &(dyn Evaluator + Sync) = &e;
        let a = Dcs::compute(d, &grid, datum_point(&e.car), Scale::Absolute).unwrap();
        let b = Dcs::compute(&e, &grid, datum_point(&e.car), Scale::Absolute).unwrap();
        assert_eq!(a, b);
    }

    #[test]
    fn hifi_map_equals_point_evaluations() {
        let car = Car::datum();
        let road = Road {
            class: RoadClass::C,
            ..Road::default()
        };
        let e = HiFi::new(&car, &road).unwrap();
        let grid = Grid::parse("12000:36000:5", "800:3200:4").unwrap();
        let map = Dcs::compute(&e, &grid, datum_point(&car), Scale::Absolute).unwrap();
        assert_eq!(assert_matches_points(&e, &map), 0.0);
        println!("hifi 5 x 4 map: all 60 values bitwise equal to point evaluations");
        assert_eq!(map.evaluator, "full");
        assert_eq!(
            map.datum.criteria,
            e.evaluate(car.front.spring, car.front.damper).unwrap()
        );
    }

    #[test]
    fn relative_map_is_absolute_over_datum() {
        let e = lofi();
        let grid = Grid::parse("10000:40000:9", "500:4000:7").unwrap();
        let d = datum_point(&e.car);
        let abs = Dcs::compute(&e, &grid, d, Scale::Absolute).unwrap();
        let rel = Dcs::compute(&e, &grid, d, Scale::Relative).unwrap();
        assert_eq!(rel.scale, Scale::Relative);
        assert_eq!(rel.datum, abs.datum);
        let dc = abs.datum.criteria.to_array();
        for (k, dk) in dc.iter().enumerate() {
            for (r, a) in rel.field(k).iter().zip(abs.field(k)) {
                assert_eq!(*r, a / dk);
            }
        }
        // Back to absolute within one rounding.
        let back = rel.to_scale(Scale::Absolute);
        for k in 0..3 {
            for (b, a) in back.field(k).iter().zip(abs.field(k)) {
                assert!(((b - a) / a).abs() <= 2.3e-16, "{b} {a}");
            }
        }
        // A grid through the datum reads exactly 1 there.
        let g = Grid::parse(
            &format!("{}:{}:2", d.0, 2.0 * d.0),
            &format!("{}:{}:2", d.1, 2.0 * d.1),
        )
        .unwrap();
        let r = Dcs::compute(&e, &g, d, Scale::Relative).unwrap();
        assert_eq!(r.criteria_at(0, 0).to_array(), [1.0; 3]);
    }

    /// Wraps an evaluator: sleeps `delay_us` per point (so the threaded path is taken),
    /// fails where `ks >= fail.0 && cs >= fail.1`, and records which threads evaluated.
    struct Probe<E> {
        inner: E,
        delay_us: u64,
        fail: (f64, f64),
        threads: std::sync::Mutex<std::collections::HashSet<std::thread::ThreadId>>,
    }

    impl<E> Probe<E> {
        fn new(inner: E, delay_us: u64, fail: (f64, f64)) -> Self {
            Probe {
                inner,
                delay_us,
                fail,
                threads: Default::default(),
            }
        }
        fn threads_used(&self) -> usize {
            self.threads.lock().unwrap().len()
        }
    }

    impl<E: Evaluator> Evaluator for Probe<E> {
        fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
            std::thread::sleep(std::time::Duration::from_micros(self.delay_us));
            self.threads
                .lock()
                .unwrap()
                .insert(std::thread::current().id());
            if ks >= self.fail.0 && cs >= self.fail.1 {
                return Err(RideError::Numerical("model unstable".into()));
            }
            self.inner.evaluate(ks, cs)
        }
        fn name(&self) -> String {
            self.inner.name()
        }
    }

    #[test]
    fn threaded_path_equals_point_evaluations() {
        // 300 us a point: a 5-point row takes 1.5 ms, so the other rows go to threads.
        let e = lofi();
        let grid = Grid::parse("10000:40000:5", "500:4000:12").unwrap();
        let d = datum_point(&e.car);
        let one = Dcs::compute_with_threads(&e, &grid, d, Scale::Absolute, 1).unwrap();
        for threads in [2, 3, 4] {
            let p = Probe::new(e.clone(), 300, (f64::INFINITY, 0.0));
            let map = Dcs::compute_with_threads(&p, &grid, d, Scale::Absolute, threads).unwrap();
            assert!(
                p.threads_used() > 1,
                "threads {threads}: {}",
                p.threads_used()
            );
            assert_eq!(map, one);
            assert_eq!(assert_matches_points(&e, &map), 0.0);
        }
    }

    #[test]
    fn a_failed_point_names_the_point() {
        let grid = Grid::parse("1:5:5", "10:50:5").unwrap();
        let ok = |ks: f64, cs: f64| Criteria {
            bacc: ks,
            dtl: cs,
            sws: 1.0,
        };
        struct Plain<F>(F);
        impl<F: Fn(f64, f64) -> Criteria> Evaluator for Plain<F> {
            fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
                Ok((self.0)(ks, cs))
            }
            fn name(&self) -> String {
                "plain".into()
            }
        }
        for (threads, delay_us) in [(1, 0), (2, 0), (2, 400), (3, 400), (5, 400)] {
            let e = Dcs::compute_with_threads(
                &Probe::new(Plain(ok), delay_us, (3.0, 20.0)),
                &grid,
                (1.0, 10.0),
                Scale::Absolute,
                threads,
            )
            .unwrap_err()
            .to_string();
            assert_eq!(
                e, "map point ks = 3 N/m, cs = 20 N s/m (column 2, row 1): model unstable",
                "threads {threads}"
            );
        }
        let e = Dcs::compute(
            &Probe::new(Plain(ok), 0, (0.0, 0.0)),
            &grid,
            (2.0, 20.0),
            Scale::Absolute,
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.starts_with("datum point (ks = 2 N/m, cs = 20 N s/m)"),
            "{e}"
        );
        // A field error keeps its field.
        let lo = lofi();
        let mut bad = lo.clone();
        bad.car.front.unsprung_mass = -1.0;
        let e = Dcs::compute(&bad, &grid, (1.0, 10.0), Scale::Absolute).unwrap_err();
        assert!(
            matches!(e, RideError::Field { ref field, .. } if field == "mu"),
            "{e}"
        );
        assert!(e.to_string().contains("at datum point"), "{e}");
    }
}
