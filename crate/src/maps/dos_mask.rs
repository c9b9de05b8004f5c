//! Design objective space (DOS) on a map: which design objectives each grid point breaks
//! (a bitmask per point), counts per objective, the feasible set in the BAcc-DTL plane,
//! and, when nothing is feasible, which objective binds everywhere.
//!
//! Each point's broken objectives are exactly [`DesignObjectives::broken`] at that point,
//! on the map's absolute criteria.

use super::dcs::{Dcs, Scale};
use super::grid::Grid;
use crate::dos::{DesignObjectives, DosContext, Objective};
use crate::error::Result;
use crate::evaluate::Criteria;
use serde::{Deserialize, Serialize};

/// Every objective in bit order: objective `OBJECTIVE_BITS[b]` is bit `1 << b` of a mask.
pub const OBJECTIVE_BITS: [Objective; 8] = [
    Objective::SwsLimit,
    Objective::BounceBand,
    Objective::DampingBand,
    Objective::BaccDatum,
    Objective::DtlDatum,
    Objective::SwsDatum,
    Objective::DtlMargin,
    Objective::Travel,
];

/// The mask bit of one objective (see [`OBJECTIVE_BITS`]).
pub fn objective_bit(o: Objective) -> u8 {
    match o {
        Objective::SwsLimit => 1,
        Objective::BounceBand => 1 << 1,
        Objective::DampingBand => 1 << 2,
        Objective::BaccDatum => 1 << 3,
        Objective::DtlDatum => 1 << 4,
        Objective::SwsDatum => 1 << 5,
        Objective::DtlMargin => 1 << 6,
        Objective::Travel => 1 << 7,
    }
}

/// The objective's name as serialised (`sws_limit`, `bounce_band`, ...).
pub fn objective_name(o: Objective) -> &'static str {
    match o {
        Objective::SwsLimit => "sws_limit",
        Objective::BounceBand => "bounce_band",
        Objective::DampingBand => "damping_band",
        Objective::BaccDatum => "bacc_datum",
        Objective::DtlDatum => "dtl_datum",
        Objective::SwsDatum => "sws_datum",
        Objective::DtlMargin => "dtl_margin",
        Objective::Travel => "travel",
    }
}

/// The objectives set in `mask`, in bit order.
pub(crate) fn objectives_in(mask: u8) -> Vec<Objective> {
    OBJECTIVE_BITS
        .iter()
        .copied()
        .filter(|&o| mask & objective_bit(o) != 0)
        .collect()
}

/// How many grid points break one objective.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct ObjectiveCount {
    /// The objective.
    pub objective: Objective,
    /// Its mask bit.
    pub bit: u8,
    /// Points that break it (possibly with others).
    pub broken: usize,
}

/// Counts over the grid.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct DosSummary {
    /// Grid points.
    pub total: usize,
    /// Points that meet every active objective.
    pub feasible: usize,
    /// Per active objective (in bit order), the points that break it.
    pub counts: Vec<ObjectiveCount>,
    /// When nothing is feasible: the objectives broken at every point (may be empty when
    /// only their combination excludes every point).
    pub binding_everywhere: Vec<Objective>,
    /// When nothing is feasible: a sentence saying why, for the page and the CLI.
    pub message: Option<String>,
}

/// A feasible design in the objective (BAcc-DTL) plane, with its design variables.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FeasiblePoint {
    /// Front spring rate, N/m.
    pub ks: f64,
    /// Front damper rate, N s/m.
    pub cs: f64,
    /// RMS body acceleration, m/s^2.
    pub bacc: f64,
    /// RMS dynamic tyre load, N.
    pub dtl: f64,
    /// RMS suspension working space, m.
    pub sws: f64,
}

/// The feasibility mask over a map's grid.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DosMap {
    /// The grid (same layout as the map: row-major, Cs rows, Ks columns).
    pub grid: Grid,
    /// The objectives as given.
    pub objectives: DesignObjectives,
    /// The objectives switched on, in bit order.
    pub active: Vec<Objective>,
    /// Per point, the bits ([`objective_bit`]) of the objectives it breaks; 0 is feasible.
    pub mask: Vec<u8>,
    /// Counts per objective.
    pub summary: DosSummary,
    /// The feasible points, in grid order, with absolute criteria.
    pub feasible_set: Vec<FeasiblePoint>,
}

impl DosMap {
    /// The mask of `map` (its absolute values: a relative map is multiplied back by the
    /// datum's criteria) under `objectives` in the car context `ctx`.
    pub fn new(map: &Dcs, objectives: &DesignObjectives, ctx: &DosContext) -> Result<DosMap> {
        objectives.validate()?;
        map.grid.validate()?;
        let abs;
        let map = if map.scale == Scale::Absolute {
            map
        } else {
            abs = map.to_scale(Scale::Absolute);
            &abs
        };
        let g = map.grid;
        let mut mask = Vec::with_capacity(g.len());
        let mut feasible_set = Vec::new();
        for j in 0..g.cs.n {
            for i in 0..g.ks.n {
                let (ks, cs) = g.point(i, j);
                let c: Criteria = map.criteria_at(i, j);
                // Exactly `objectives.broken(..)`, without allocating per point.
                let mut bits = 0u8;
                objectives.each_constraint(ctx, ks, cs, &c, |o, g| {
                    if g > 0.0 {
                        bits |= objective_bit(o);
                    }
                });
                if bits == 0 {
                    feasible_set.push(FeasiblePoint {
                        ks,
                        cs,
                        bacc: c.bacc,
                        dtl: c.dtl,
                        sws: c.sws,
                    });
                }
                mask.push(bits);
            }
        }
        // The active objectives: those `constraints` lists (probed at the datum).
        let probe = objectives.constraints(ctx, map.datum.ks, map.datum.cs, &ctx.datum);
        let active: Vec<Objective> = OBJECTIVE_BITS
            .iter()
            .copied()
            .filter(|o| probe.iter().any(|(p, _)| p == o))
            .collect();
        let summary = summarize(&mask, &active);
        Ok(DosMap {
            grid: g,
            objectives: objectives.clone(),
            active,
            mask,
            summary,
            feasible_set,
        })
    }

    /// A mask made elsewhere (the robust DOS of issue #16: the OR of every case's
    /// mask) with its counts; `feasible_set` lists the points where `mask` is 0.
    pub(crate) fn from_mask(
        grid: Grid,
        objectives: &DesignObjectives,
        active: Vec<Objective>,
        mask: Vec<u8>,
        feasible_set: Vec<FeasiblePoint>,
    ) -> DosMap {
        let summary = summarize(&mask, &active);
        DosMap {
            grid,
            objectives: objectives.clone(),
            active,
            mask,
            summary,
            feasible_set,
        }
    }

    /// The objectives broken at Ks column `i`, Cs row `j` (empty when feasible).
    #[cfg(test)]
    pub(crate) fn broken_at(&self, i: usize, j: usize) -> Vec<Objective> {
        objectives_in(self.mask[self.grid.index(i, j)])
    }

    /// True when the point at Ks column `i`, Cs row `j` meets every active objective.
    #[cfg(test)]
    pub(crate) fn is_feasible(&self, i: usize, j: usize) -> bool {
        self.mask[self.grid.index(i, j)] == 0
    }

    /// 1 where feasible, 0 where not, as a field for [`super::contour`] (its 0.5 contour
    /// outlines the feasible region).
    pub(crate) fn feasible_field(&self) -> Vec<f64> {
        self.mask
            .iter()
            .map(|&m| if m == 0 { 1.0 } else { 0.0 })
            .collect()
    }
}

fn summarize(mask: &[u8], active: &[Objective]) -> DosSummary {
    let total = mask.len();
    let feasible = mask.iter().filter(|&&m| m == 0).count();
    let counts: Vec<ObjectiveCount> = active
        .iter()
        .map(|&objective| {
            let bit = objective_bit(objective);
            ObjectiveCount {
                objective,
                bit,
                broken: mask.iter().filter(|&&m| m & bit != 0).count(),
            }
        })
        .collect();
    let (binding_everywhere, message) = if feasible > 0 || total == 0 {
        (Vec::new(), None)
    } else {
        let everywhere: Vec<Objective> = counts
            .iter()
            .filter(|c| c.broken == total)
            .map(|c| c.objective)
            .collect();
        let message = if everywhere.is_empty() {
            let most = counts.iter().rev().max_by_key(|c| c.broken);
            let most = most.map_or(String::new(), |c| {
                format!(
                    "; most often broken: {} ({} of {total} points)",
                    c.objective.label(),
                    c.broken
                )
            });
            format!(
                "no feasible design on the grid: no single objective is broken everywhere, \
                 but together they exclude every point{most}"
            )
        } else {
            let labels: Vec<&str> = everywhere.iter().map(|o| o.label()).collect();
            format!(
                "no feasible design on the grid: {} broken at every point",
                labels.join(", ")
            )
        };
        (everywhere, Some(message))
    };
    DosSummary {
        total,
        feasible,
        counts,
        binding_everywhere,
        message,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::LoFi;
    use crate::car::Car;
    use crate::evaluate::Evaluator;
    use crate::road::{Road, RoadClass};

    fn setup(class: RoadClass) -> (LoFi, Dcs, DosContext) {
        let car = Car::datum();
        let e = LoFi {
            car: car.clone(),
            road: Road {
                class,
                ..Road::default()
            },
        };
        let grid = Grid::parse("10000:40000:31", "500:4000:29").unwrap();
        let map = Dcs::compute(
            &e,
            &grid,
            (car.front.spring, car.front.damper),
            Scale::Absolute,
        )
        .unwrap();
        let q = car.quarter();
        let ctx = DosContext {
            sprung_mass: q.ms,
            tire_stiffness: q.kt,
            datum: map.datum.criteria,
            static_wheel_load: car.front_wheel_load(),
        };
        (e, map, ctx)
    }

    #[test]
    fn mask_agrees_with_broken_point_by_point() {
        let (e, map, ctx) = setup(RoadClass::B);
        let all_on = DesignObjectives {
            sws_limit: Some(0.0065),
            bounce_band: Some((0.9, 1.3)),
            damping_band: Some((0.25, 0.45)),
            no_worse_than_datum: [true, true, false],
            ..DesignObjectives::default()
        };
        // RMS DTL at most F_static / 14 (356 N) and 3 sigma of SWS within 18 mm.
        let limits = DesignObjectives {
            sws_limit: None,
            dtl_margin: Some(14.0),
            travel: Some((0.018, 3.0)),
            ..DesignObjectives::default()
        };
        for objectives in [DesignObjectives::default(), all_on, limits] {
            let dos = DosMap::new(&map, &objectives, &ctx).unwrap();
            let mut seen = 0u8;
            for j in 0..map.grid.cs.n {
                for i in 0..map.grid.ks.n {
                    let (ks, cs) = map.grid.point(i, j);
                    let c = e.evaluate(ks, cs).unwrap();
                    let want = objectives.broken(&ctx, ks, cs, &c);
                    assert_eq!(dos.broken_at(i, j), want, "({i}, {j})");
                    assert_eq!(dos.is_feasible(i, j), want.is_empty());
                    seen |= dos.mask[map.grid.index(i, j)];
                }
            }
            // Each active objective is broken somewhere and met somewhere on this grid.
            assert_eq!(objectives_in(seen), dos.active);
            let feasible = dos.mask.iter().filter(|&&m| m == 0).count();
            assert_eq!(dos.summary.feasible, feasible);
            assert_eq!(dos.feasible_set.len(), feasible);
            assert!(feasible > 0 && feasible < map.grid.len());
            for c in &dos.summary.counts {
                assert!(c.broken > 0 && c.broken < map.grid.len(), "{c:?}");
            }
            assert!(dos.summary.message.is_none());
            println!(
                "mask {} points: {} feasible, counts {:?}",
                map.grid.len(),
                feasible,
                dos.summary
                    .counts
                    .iter()
                    .map(|c| (objective_name(c.objective), c.broken))
                    .collect::<Vec<_>>()
            );
            for p in &dos.feasible_set {
                let c = e.evaluate(p.ks, p.cs).unwrap();
                assert!(objectives.broken(&ctx, p.ks, p.cs, &c).is_empty());
                assert_eq!((p.bacc, p.dtl, p.sws), (c.bacc, c.dtl, c.sws));
            }
            // The same mask from the relative map.
            let rel = DosMap::new(&map.to_scale(Scale::Relative), &objectives, &ctx).unwrap();
            let differ = rel
                .mask
                .iter()
                .zip(&dos.mask)
                .filter(|(a, b)| a != b)
                .count();
            assert_eq!(differ, 0);
        }
    }

    #[test]
    fn class_c_says_sws_binds_everywhere() {
        // METHOD.md: at class C no design in the default box meets the 7 mm SWS limit.
        let (_, map, ctx) = setup(RoadClass::C);
        let dos = DosMap::new(&map, &DesignObjectives::default(), &ctx).unwrap();
        assert_eq!(dos.summary.feasible, 0);
        assert!(dos.feasible_set.is_empty());
        assert_eq!(dos.summary.binding_everywhere, vec![Objective::SwsLimit]);
        let m = dos.summary.message.clone().unwrap();
        assert!(m.contains("SWS limit broken at every point"), "{m}");
        assert_eq!(dos.summary.counts[0].broken, map.grid.len());
    }

    #[test]
    fn combination_without_a_single_binding_objective_is_explained() {
        // BAcc rises and DTL falls with Ks; the datum sits between grid columns, so each
        // point is worse than the datum in exactly one of the two.
        let grid = Grid::parse("1:4:4", "1:2:2").unwrap();
        let ks: Vec<f64> = (0..grid.len())
            .map(|k| grid.point(grid.indices(k).0, 0).0)
            .collect();
        let datum = Criteria {
            bacc: 2.5,
            dtl: 7.5,
            sws: 1.0,
        };
        let map = Dcs {
            evaluator: "synthetic".into(),
            grid,
            scale: Scale::Absolute,
            datum: super::super::dcs::DatumPoint {
                ks: 2.5,
                cs: 1.5,
                criteria: datum,
            },
            bacc: ks.clone(),
            dtl: ks.iter().map(|k| 10.0 - k).collect(),
            sws: vec![1.0; grid.len()],
        };
        let ctx = DosContext {
            sprung_mass: 400.0,
            tire_stiffness: 2e5,
            datum,
            static_wheel_load: 4_000.0,
        };
        let objectives = DesignObjectives {
            sws_limit: None,
            no_worse_than_datum: [true, true, false],
            ..DesignObjectives::default()
        };
        let dos = DosMap::new(&map, &objectives, &ctx).unwrap();
        assert_eq!(dos.active, vec![Objective::BaccDatum, Objective::DtlDatum]);
        assert_eq!(dos.summary.feasible, 0);
        assert!(dos.summary.binding_everywhere.is_empty());
        assert_eq!(dos.summary.counts[0].broken, 4);
        assert_eq!(dos.summary.counts[1].broken, 4);
        let m = dos.summary.message.unwrap();
        assert!(m.contains("together they exclude every point"), "{m}");
        assert!(
            m.contains("most often broken: BAcc no worse than datum (4 of 8 points)"),
            "{m}"
        );
        // No objective switched on: everything feasible.
        let none = DesignObjectives {
            sws_limit: None,
            ..DesignObjectives::default()
        };
        let dos = DosMap::new(&map, &none, &ctx).unwrap();
        assert!(dos.active.is_empty());
        assert_eq!(dos.summary.feasible, map.grid.len());
        assert!(dos.summary.message.is_none());
    }

    #[test]
    fn bits_round_trip() {
        for (b, o) in OBJECTIVE_BITS.iter().enumerate() {
            assert_eq!(objective_bit(*o), 1 << b);
            assert_eq!(objectives_in(1 << b), vec![*o]);
            assert_eq!(serde_json::to_value(o).unwrap(), objective_name(*o));
        }
        assert_eq!(
            objectives_in(0b10_0001),
            vec![Objective::SwsLimit, Objective::SwsDatum]
        );
    }
}
