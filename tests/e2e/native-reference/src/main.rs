//! Prints `{"quarter": Report, "full": Report}` for a car file and road, like
//! `ridelab eval --model quarter|full --car FILE --class C --speed V --json`.
//! Usage: native-reference CAR.json CLASS SPEED [TRACKS]

use ridelab::analysis::{report, ModelKind};
use ridelab::{Car, Road, RoadClass, Tracks};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 4 {
        eprintln!("usage: native-reference CAR.json CLASS SPEED [TRACKS]");
        std::process::exit(2);
    }
    let run = || -> ridelab::Result<String> {
        let text = std::fs::read_to_string(&args[1])
            .map_err(|e| ridelab::RideError::field("car", e.to_string()))?;
        let car = Car::from_json(&text)?;
        let speed: f64 = args[3]
            .parse()
            .map_err(|_| ridelab::RideError::field("speed", "not a number"))?;
        let road = Road {
            class: RoadClass::parse(&args[2])?,
            speed,
            tracks: Tracks::parse(args.get(4).map(String::as_str).unwrap_or("correlated"))?,
        };
        let q = report(ModelKind::Quarter, &car, &road)?;
        let f = report(ModelKind::Full, &car, &road)?;
        Ok(serde_json::json!({ "quarter": q, "full": f }).to_string())
    };
    match run() {
        Ok(s) => println!("{s}"),
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }
}
