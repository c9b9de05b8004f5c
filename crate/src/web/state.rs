//! The page's state as the JS side sends it, and its conversion into core types.
//!
//! Units follow the core (SI): `ks` N/m, `cs` N s/m, `speed` m/s, `swsLimit` m.
//! The UI converts to kN/m, kNs/m and mm for display only.

use crate::car::Car;
use crate::design::DesignBox;
use crate::dos::{DesignObjectives, DosContext};
use crate::error::{Result, RideError};
use crate::evaluate::Evaluator;
use crate::road::{Road, RoadClass, Tracks};
use crate::LoFi;
use serde::{Deserialize, Serialize};

/// The JS names of the [`State`] fields.
pub const STATE_FIELDS: [&str; 12] = [
    "car", "carJson", "ks", "cs", "class", "speed", "tracks", "ksMin", "ksMax", "csMin", "csMax",
    "swsLimit",
];

/// Everything the page needs to define one view: car, design point, road, design box
/// and the SWS objective. Field names are camelCase on the JS side.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
pub struct State {
    /// A preset name ("sedan", "compact", "suv") or "custom" (then `car_json` is the car file).
    pub car: String,
    /// The car file when `car` is "custom".
    #[serde(default)]
    pub car_json: Option<String>,
    /// Front spring rate, N/m.
    pub ks: f64,
    /// Front damper rate, N s/m.
    pub cs: f64,
    /// ISO 8608 class "A".."H".
    pub class: String,
    /// Vehicle speed, m/s.
    pub speed: f64,
    /// "correlated" or "independent".
    pub tracks: String,
    /// Design box: lowest Ks, N/m (default [`DesignBox::default`]).
    #[serde(default)]
    pub ks_min: Option<f64>,
    /// Design box: highest Ks, N/m.
    #[serde(default)]
    pub ks_max: Option<f64>,
    /// Design box: lowest Cs, N s/m.
    #[serde(default)]
    pub cs_min: Option<f64>,
    /// Design box: highest Cs, N s/m.
    #[serde(default)]
    pub cs_max: Option<f64>,
    /// RMS SWS limit, m (default 0.007).
    #[serde(default)]
    pub sws_limit: Option<f64>,
}

impl Default for State {
    /// The datum car at its own front spring and damper, class B at 20 m/s, correlated.
    fn default() -> Self {
        let car = Car::datum();
        let road = Road::default();
        let b = DesignBox::default();
        State {
            car: crate::car::PRESETS[0].0.to_string(),
            car_json: None,
            ks: car.front.spring,
            cs: car.front.damper,
            class: format!("{:?}", road.class),
            speed: road.speed,
            tracks: "correlated".into(),
            ks_min: Some(b.ks_min),
            ks_max: Some(b.ks_max),
            cs_min: Some(b.cs_min),
            cs_max: Some(b.cs_max),
            sws_limit: DesignObjectives::default().sws_limit,
        }
    }
}

/// The core objects behind a [`State`].
#[derive(Debug, Clone, PartialEq)]
pub struct Scenario {
    /// The datum car: the chosen car with its own front spring and damper.
    pub datum: Car,
    /// The datum car with the front set to the state's design.
    pub design: Car,
    /// The road.
    pub road: Road,
    /// The design box.
    pub dbox: DesignBox,
    /// The design objectives (SWS limit only, for now).
    pub objectives: DesignObjectives,
}

impl State {
    /// The datum car (a preset or the custom car file), validated.
    pub fn datum_car(&self) -> Result<Car> {
        if self.car == "custom" {
            let text = self
                .car_json
                .as_deref()
                .ok_or_else(|| RideError::field("car", "'custom' needs a car file (carJson)"))?;
            Car::from_json(text)
        } else {
            Car::preset(&self.car)
        }
    }

    /// The road, validated.
    pub fn road(&self) -> Result<Road> {
        let road = Road {
            class: RoadClass::parse(&self.class)?,
            speed: self.speed,
            tracks: Tracks::parse(&self.tracks)?,
        };
        road.validate()?;
        Ok(road)
    }

    /// The design box, validated.
    pub fn design_box(&self) -> Result<DesignBox> {
        let d = DesignBox::default();
        let b = DesignBox {
            ks_min: self.ks_min.unwrap_or(d.ks_min),
            ks_max: self.ks_max.unwrap_or(d.ks_max),
            cs_min: self.cs_min.unwrap_or(d.cs_min),
            cs_max: self.cs_max.unwrap_or(d.cs_max),
        };
        b.validate()?;
        Ok(b)
    }

    /// The design objectives, validated.
    pub fn objectives(&self) -> Result<DesignObjectives> {
        let o = DesignObjectives {
            sws_limit: self.sws_limit,
            ..DesignObjectives::default()
        };
        o.validate()?;
        Ok(o)
    }

    /// Everything at once; the first error names its field.
    pub fn scenario(&self) -> Result<Scenario> {
        let datum = self.datum_car()?;
        let road = self.road()?;
        let design = datum.with_front(self.ks, self.cs)?;
        Ok(Scenario {
            datum,
            design,
            road,
            dbox: self.design_box()?,
            objectives: self.objectives()?,
        })
    }
}

impl Scenario {
    /// The LoFi evaluator of the datum car on the road.
    pub fn lofi(&self) -> LoFi {
        LoFi {
            car: self.datum.clone(),
            road: self.road,
        }
    }

    /// What the design objectives need besides the criteria (datum by the LoFi model).
    pub fn lofi_dos_context(&self) -> Result<DosContext> {
        let q = self.datum.quarter();
        Ok(DosContext {
            sprung_mass: q.ms,
            tire_stiffness: q.kt,
            datum: self.lofi().evaluate(q.ks, q.cs)?,
        })
    }
}

/// A LoFi design map: the three criteria and feasibility over an `nx` x `ny` grid of
/// cell centres, `ks_i = ks_min + (i + 1/2) (ks_max - ks_min) / nx` (likewise `cs_j`).
#[derive(Debug, Clone, PartialEq)]
pub struct LoFiMap {
    /// Cells along Ks.
    pub nx: usize,
    /// Cells along Cs.
    pub ny: usize,
    /// `[bacc plane, dtl plane, sws plane]`, each row-major with `j` (Cs) slow and
    /// `i` (Ks) fast, j = 0 at the lowest Cs: index `c nx ny + j nx + i`.
    pub values: Vec<f64>,
    /// 1 where the design meets every active objective, 0 where not; index `j nx + i`.
    pub feasible: Vec<u8>,
}

/// Largest grid side accepted from the page (a 1024 x 1024 map is 1 M LoFi evaluations).
pub const MAX_GRID: usize = 1024;

/// Computes the LoFi map of `scenario` on an `nx` x `ny` grid.
pub fn lofi_map(scenario: &Scenario, nx: usize, ny: usize) -> Result<LoFiMap> {
    for (name, n) in [("nx", nx), ("ny", ny)] {
        if n == 0 || n > MAX_GRID {
            return Err(RideError::field(
                name,
                format!("grid size must be 1..{MAX_GRID} (got {n})"),
            ));
        }
    }
    let ev = scenario.lofi();
    let ctx = scenario.lofi_dos_context()?;
    let cells = nx * ny;
    let mut values = vec![0.0; 3 * cells];
    let mut feasible = vec![0u8; cells];
    for j in 0..ny {
        for i in 0..nx {
            let (ks, cs) = scenario
                .dbox
                .scale((i as f64 + 0.5) / nx as f64, (j as f64 + 0.5) / ny as f64);
            let c = ev.evaluate(ks, cs)?;
            let k = j * nx + i;
            values[k] = c.bacc;
            values[cells + k] = c.dtl;
            values[2 * cells + k] = c.sws;
            feasible[k] = u8::from(scenario.objectives.broken(&ctx, ks, cs, &c).is_empty());
        }
    }
    Ok(LoFiMap {
        nx,
        ny,
        values,
        feasible,
    })
}
