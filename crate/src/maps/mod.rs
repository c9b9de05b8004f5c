//! Design maps (METHOD.md section 3): the design criteria space (DCS) — BAcc, DTL and SWS
//! on a Ks x Cs grid, absolute or relative to the datum car — the design objective space
//! (DOS) as a feasibility mask over the same grid with the feasible set in the BAcc-DTL
//! plane, and contour lines of any field.
//!
//! Every field on a map is a `Vec<f64>` laid out **row-major with Cs rows and Ks columns**:
//! the value at Ks index `i`, Cs index `j` is at `j * grid.ks.n + i` ([`Grid::index`]).
//!
//! Any [`crate::Evaluator`] that is `Sync` maps (LoFi, HiFi, a surrogate, or
//! `&(dyn Evaluator + Sync)`); native targets spread the rows over scoped threads,
//! wasm32 runs them on the calling thread.
//!
//! ```
//! use ridelab::maps::{Dcs, DosMap, Grid, Scale, contour, auto_levels};
//! use ridelab::{Car, LoFi, Road};
//! use ridelab::dos::{DesignObjectives, DosContext};
//!
//! let car = Car::datum();
//! let lofi = LoFi::new(&car, &Road::default());
//! let grid = Grid::parse("10000:40000:31", "500:4000:31")?;
//! let map = Dcs::compute(&lofi, &grid, (car.front.spring, car.front.damper), Scale::Absolute)?;
//! let dos = DosMap::new(&map, &DesignObjectives::default(), &DosContext::new(&car, map.datum.criteria))?;
//! assert!(dos.summary.feasible > 0);
//! let levels = auto_levels(&map.bacc, 8);
//! let lines = contour(&grid, &map.bacc, levels[0])?;
//! assert!(!lines.polylines.is_empty());
//! # Ok::<(), ridelab::RideError>(())
//! ```

pub mod contour;
pub mod dcs;
pub mod dos_mask;
pub mod grid;

pub(crate) use contour::nice_levels;
pub use contour::{auto_levels, contour, contours, Contour, Polyline};
pub(crate) use dcs::map_grid;
pub use dcs::{default_threads, evaluate_grid, DatumPoint, Dcs, Scale};
pub use dos_mask::{
    objective_bit, objective_name, DosMap, DosSummary, FeasiblePoint, ObjectiveCount,
    OBJECTIVE_BITS,
};
pub use grid::{Axis, Grid};
