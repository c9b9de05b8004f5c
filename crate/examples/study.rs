//! A study from Rust, as `ridelab map` and `ridelab optimize` run it: the datum sedan on an
//! ISO class C road at 25 m/s with a 12 mm SWS limit, the quarter car's map on a 5 x 5 grid and the full car's
//! front with its min-max pick, both methods of one [`StudySpec`].
//!
//! `cargo run --example study`

use ridelab::analysis::ModelKind;
use ridelab::car::Car;
use ridelab::dos::DesignObjectives;
use ridelab::error::Result;
use ridelab::maps::{Axis, Grid, Scale};
use ridelab::optimize::{Method, PickRule, StmParams};
use ridelab::road::{Road, RoadClass};
use ridelab::study::{FrontAsk, FrontReport, MapAsk, StudyRoad, StudySpec};
use ridelab::surrogate::PlanSpec;

fn main() -> Result<()> {
    let road = Road {
        class: RoadClass::C,
        speed: 25.0,
        ..Road::default()
    };
    // Class C at 25 m/s breaks the default 7 mm SWS limit everywhere: allow 12 mm.
    let study = StudySpec {
        objectives: DesignObjectives {
            sws_limit: Some(0.012),
            ..DesignObjectives::default()
        },
        ..StudySpec::new(Car::datum(), StudyRoad::Iso(road))
    };
    let grid = Grid::new(
        Axis {
            min: 10_000.0,
            max: 40_000.0,
            n: 5,
        },
        Axis {
            min: 500.0,
            max: 4_000.0,
            n: 5,
        },
    )?;
    let map = study
        .map(&MapAsk {
            model: ModelKind::Quarter.into(),
            plan: PlanSpec::AudzeEglais(10),
            grid,
            scale: Scale::Absolute,
            case: None,
        })?
        .into_map();
    println!("quarter car, BAcc over the grid, m/s^2 (Cs rows, Ks columns):");
    for row in map.bacc.chunks(grid.ks.n) {
        let cells: Vec<String> = row.iter().map(|v| format!("{v:.3}")).collect();
        println!("  {}", cells.join("  "));
    }
    let front = study.front(&FrontAsk {
        evaluator: ModelKind::Full.into(),
        plan: PlanSpec::AudzeEglais(10),
        method: Method::Stm(StmParams {
            grid: 41,
            levels: 2,
        }),
        pick: PickRule::MinMax,
        adaptive: None,
    })?;
    if let FrontReport::One(r) = front.front {
        let p = &r.study.pick;
        println!(
            "full car: {} front points; min-max pick Ks {:.0} N/m, Cs {:.0} N s/m: \
             BAcc {:+.1} %, DTL {:+.1} %, SWS {:+.1} % against the datum",
            r.study.front.len(),
            p.ks,
            p.cs,
            p.change_percent[0],
            p.change_percent[1],
            p.change_percent[2]
        );
    }
    Ok(())
}
