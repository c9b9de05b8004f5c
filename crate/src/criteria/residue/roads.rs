//! The residue route of one model on several roads (issue #16: one loaded car at several
//! operating points): what a point needs that does not depend on the road is computed
//! once, the rest per road, by the same operations as each road's own route.
//!
//! The road enters a family ([`ResidueFamily`]) only through the wheel delays
//! `tau_g = L_g / v` and the intensity `W = 2 pi^2 Gd(n0) n0^2 v` of the white road
//! velocity: `D(s)`, its roots `lambda_k`, the residues `rho_gk`, the static gains `G_g`
//! and the table `S_km = -1 / (lambda_k + lambda_m)` belong to the model alone. So at
//! each design
//!
//! - the roots, `S` and the residues are computed once for all roads;
//! - the delay terms (`e^{lambda_k D_gl}` and the double sums of the module doc of
//!   [`super`], without `W`) once per distinct set of delays, i.e. once per speed: roads
//!   of one speed and different ISO 8608 classes share them, as the class scales only `W`;
//! - each road's variances then add its own `W` times those terms, and its own box-box
//!   terms `W G_g G_l min(tau_g, tau_l)`, in its own route's order.
//!
//! Every value is computed by the same function on the same operands as in that road's
//! own [`ResidueRoute::criteria`], so each road's result (value, bound, or the reason it
//! declines) equals its own route's bit for bit.

use super::{
    add_part, certify, Certified, DelayTerms, OnPoint, Point, Residue, ResidueFamily, ResidueRoute,
};
use crate::error::{Result, RideError};
use crate::model::N_OUT;

/// The residue routes of one model on several roads (each [`ResidueRoute`] built for one
/// road), evaluated together at each design (module doc).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ResidueRoads {
    routes: Vec<ResidueRoute>,
    /// Per road, the first road whose families have the same wheel delays.
    delays_of: Vec<usize>,
}

impl ResidueRoads {
    /// The routes `routes` (one per road) of one model; fails on none, or when their
    /// families differ in more than the road (the wheel delays and the intensity).
    pub(crate) fn new(routes: Vec<ResidueRoute>) -> Result<ResidueRoads> {
        let unsuited = |why: &str| RideError::Numerical(format!("residue roads: {why}"));
        let first = routes.first().ok_or_else(|| unsuited("needs a route"))?;
        for r in &routes[1..] {
            let same = r.parts.len() == first.parts.len()
                && r.parts
                    .iter()
                    .zip(&first.parts)
                    .all(|((a, _), (b, _))| a.same_model(b));
            if !same {
                return Err(unsuited("the routes are not of one model"));
            }
        }
        let same_delays = |a: &ResidueRoute, b: &ResidueRoute| {
            a.parts
                .iter()
                .zip(&b.parts)
                .all(|((x, _), (y, _))| x.same_delays(y))
        };
        let delays_of = (0..routes.len())
            .map(|r| {
                (0..r)
                    .find(|&q| same_delays(&routes[q], &routes[r]))
                    .unwrap_or(r)
            })
            .collect();
        Ok(ResidueRoads { routes, delays_of })
    }

    /// Per road, what its own route's [`ResidueRoute::criteria`] gives at `(ks, cs)`
    /// (N/m, N s/m), bit for bit.
    pub(crate) fn criteria(&self, ks: f64, cs: f64) -> Vec<Result<Certified>> {
        let n = self.routes.len();
        let mut sums = vec![([0.0; N_OUT], [0.0; N_OUT]); n];
        // A road is settled once a part declines or errs, as its own route returns then.
        let mut settled: Vec<Option<Result<Certified>>> = vec![None; n];
        for p in 0..self.routes[0].parts.len() {
            let on = Roads {
                roads: self,
                part: p,
                open: settled.iter().map(Option::is_none).collect(),
            };
            let open = settled.iter_mut().filter(|s| s.is_none());
            match self.routes[0].parts[p].0.at(ks, cs, on) {
                Err(e) => open.for_each(|s| *s = Some(Err(e.clone()))),
                Ok(Err(why)) => open.for_each(|s| *s = Some(Ok(Certified::Declined(why)))),
                Ok(Ok(per_road)) => {
                    for (r, residue) in per_road.into_iter().enumerate() {
                        match residue {
                            Some(Residue::Variances { var, bound }) => {
                                let (v, e) = &mut sums[r];
                                add_part(v, e, self.routes[r].parts[p].1, &var, bound);
                            }
                            Some(Residue::Declined(why)) => {
                                settled[r] = Some(Ok(Certified::Declined(why)));
                            }
                            None => {}
                        }
                    }
                }
            }
        }
        settled
            .into_iter()
            .zip(sums)
            .map(|(s, (var, err))| s.unwrap_or_else(|| Ok(certify(&var, &err))))
            .collect()
    }
}

/// Part `part` of every open road at one point: the delay terms once per set of delays,
/// then each open road's variances (`None` for a settled road).
struct Roads<'a> {
    roads: &'a ResidueRoads,
    part: usize,
    open: Vec<bool>,
}

impl OnPoint for Roads<'_> {
    type Out = Vec<Option<Residue>>;

    fn on<const NP: usize>(self, _: &ResidueFamily, point: &Point<NP>) -> Self::Out {
        let routes = &self.roads.routes;
        let mut terms: Vec<Option<DelayTerms>> = vec![None; routes.len()];
        (0..routes.len())
            .map(|r| {
                if !self.open[r] {
                    return None;
                }
                let family = &routes[r].parts[self.part].0;
                let q = self.roads.delays_of[r];
                let t = *terms[q].get_or_insert_with(|| family.delay_terms(point));
                Some(family.accumulate(point, &t))
            })
            .collect()
    }
}

impl ResidueFamily {
    /// Whether `other` is this family on another road: everything equal but the wheel
    /// delays and the intensity.
    fn same_model(&self, other: &ResidueFamily) -> bool {
        self.deg == other.deg
            && self.d0 == other.d0
            && self.e == other.e
            && self.scale == other.scale
            && self.start == other.start
            && self.sources.len() == other.sources.len()
            && self.sources.iter().zip(&other.sources).all(|(a, b)| {
                a.len() == b.len()
                    && a.iter()
                        .zip(b)
                        .all(|(x, y)| x.yr == y.yr && x.alpha == y.alpha && x.beta == y.beta)
            })
    }

    /// Whether `other` has the same wheel delays (bit for bit), so the same delay terms.
    fn same_delays(&self, other: &ResidueFamily) -> bool {
        self.sources.len() == other.sources.len()
            && self.sources.iter().zip(&other.sources).all(|(a, b)| {
                a.len() == b.len()
                    && a.iter()
                        .zip(b)
                        .all(|(x, y)| x.tau.to_bits() == y.tau.to_bits())
            })
    }
}
