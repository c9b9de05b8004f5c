//! Bounds on a command's total work, not just on each of its sizes.
//!
//! A model run is one evaluation of the LoFi, the HiFi or a surrogate at one design for
//! one case. Each command's runs are estimated from its options before any work, and the
//! estimate is refused above [`MAX_RUNS`] with a message that names the options to lower.
//! STM's count depends on the front it finds, so the optimisers also stop at
//! [`HARD_RUNS`] counted runs whatever the estimate said. Measured (release build,
//! 2-core machine, 2026-12): a HiFi run by the residue route costs 2 to 3 us, a LoFi run
//! well under 1 us, so [`MAX_RUNS`] is at most about 10 s of model time.

use crate::error::{Result, RideError};

/// Most model runs one command may ask for.
pub(crate) const MAX_RUNS: u64 = 4_000_000;

/// Most model runs one command may ask for on a measured road (`--road FILE`): there a
/// HiFi run takes the residue route with the road's shaping filters, about 4 us
/// ([`crate::road_profile::MeasuredModel`]; the default STM, 201 with 3 levels, 48 517
/// runs, took 0.17 s on the shipped slab road), a LoFi run the quarter car's closed form
/// (about 1 us), a run with the Wk-weighted comfort about 50 us (the same STM took 2.3 s),
/// the modal route where the others decline (about 0.13 ms) and the Lyapunov route where
/// a filter's partial fractions cancel (about 1.5 ms), so this is at most about 0.5 s of
/// model time, 5 s with Wk, and 150 s in that worst case.
pub const MAX_MEASURED_RUNS: u64 = 100_000;

/// [`check`] on a measured road: refuses `runs` above [`MAX_MEASURED_RUNS`].
pub fn check_measured(runs: u64, field: &str, what: &str, options: &str) -> Result<()> {
    if runs <= MAX_MEASURED_RUNS {
        return Ok(());
    }
    Err(RideError::field(
        field,
        format!(
            "{what} asks for about {} model runs on a measured road; one command takes at most {} there (about 0.5 s of model time, 5 s with --comfort wk, up to 150 s where the road's filter needs the slow route): lower {options}",
            group(runs),
            group(MAX_MEASURED_RUNS)
        ),
    ))
}

/// Counted runs at which an optimiser stops with an error, whatever the estimate.
pub(crate) const HARD_RUNS: u64 = 2 * MAX_RUNS;

/// Longest side of STM's refined lattice, `(grid - 1) 2^levels` fine cells: its front
/// has a few points per lattice step (measured: up to 4.2 per step), so this keeps a
/// front under about 150 000 points and its JSON under about 25 MB.
pub(crate) const MAX_LATTICE_SIDE: u64 = 32_768;

/// Upper estimate of STM's runs for `grid` points per variable and `levels` refinement
/// levels: the grid, then about ten runs per fine lattice step for the patches and the
/// boundary bisection, `grid^2 + 12 (grid - 1) 2^levels` (measured on the datum car:
/// 7.5 to 11.6 per step for grids 51 to 401 and 3 to 8 levels).
pub fn stm_runs(grid: usize, levels: usize) -> u64 {
    let g = grid as u64;
    g.saturating_mul(g)
        .saturating_add(12u64.saturating_mul(lattice_side(grid, levels)))
}

/// STM's refined lattice side `(grid - 1) 2^levels`, fine cells.
pub(crate) fn lattice_side(grid: usize, levels: usize) -> u64 {
    (grid.saturating_sub(1) as u64).saturating_mul(1u64 << levels.min(40))
}

/// Refuses `runs` above [`MAX_RUNS`]: the error names `field` (the first option to
/// lower), says what asked for the runs and which options set them.
pub fn check(runs: u64, field: &str, what: &str, options: &str) -> Result<()> {
    if runs <= MAX_RUNS {
        return Ok(());
    }
    Err(RideError::field(
        field,
        format!(
            "{what} asks for about {} model runs; one command takes at most {} (about 10 s of model time): lower {options}",
            group(runs),
            group(MAX_RUNS)
        ),
    ))
}

/// A count with thin spaces between thousands, as the README writes them.
pub(crate) fn group(n: u64) -> String {
    let s = n.to_string();
    let mut out = String::new();
    for (i, c) in s.chars().enumerate() {
        if i > 0 && (s.len() - i).is_multiple_of(3) {
            out.push(' ');
        }
        out.push(c);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn estimates_and_messages() {
        // The default STM (201, 3) and the page's plane (61, 2).
        assert_eq!(stm_runs(201, 3), 40_401 + 12 * 1_600);
        assert_eq!(stm_runs(61, 2), 3_721 + 12 * 240);
        assert!(check(stm_runs(201, 3), "grid", "STM", "--grid").is_ok());
        let e = check(
            stm_runs(1001, 10),
            "grid",
            "STM on 1001 x 1001 with 10 levels",
            "--grid or --levels",
        )
        .unwrap_err()
        .to_string();
        assert_eq!(
            e,
            "grid: STM on 1001 x 1001 with 10 levels asks for about 13 290 001 model runs; one command takes at most 4 000 000 (about 10 s of model time): lower --grid or --levels"
        );
        assert_eq!(group(999), "999");
        assert_eq!(group(1_000), "1 000");
        assert_eq!(lattice_side(2001, 10), 2_048_000);
        assert_eq!(stm_runs(usize::MAX, 60), u64::MAX);
    }
}
