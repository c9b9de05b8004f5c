use ridelab::criteria::*;
use ridelab::model::*;
use ridelab::*;
fn main() {
    let car = Car::datum();
    let road = Road::default();
    let q = car.quarter();
    let cf = quarter_car_rms(&q, road.intensity());
    let ex = criteria_exact(&quarter_car(&q), &road).unwrap();
    let sp = criteria_spectral(&quarter_car(&q), &road, 1e-10).unwrap();
    println!("quarter cf {:?}\n ex {:?}\n sp {:?}", cf, ex, sp);
    let m = full_car(&car);
    let t = std::time::Instant::now();
    let ex = criteria_exact(&m, &road).unwrap();
    println!("full exact {:?} {:?}", ex, t.elapsed());
    for rtol in [1e-4, 1e-6, 1e-8, 1e-10] {
        let t = std::time::Instant::now();
        let sp = criteria_spectral(&m, &road, rtol).unwrap();
        println!(
            "full spec {rtol} {:?} {:?} rel {:e}",
            sp,
            t.elapsed(),
            (sp.criteria.dtl / ex.dtl - 1.0)
                .abs()
                .max((sp.criteria.bacc / ex.bacc - 1.0).abs())
                .max((sp.criteria.sws / ex.sws - 1.0).abs())
        );
    }
    let road2 = Road {
        tracks: Tracks::Independent,
        ..road
    };
    let ex = criteria_exact(&m, &road2).unwrap();
    let sp = criteria_spectral(&m, &road2, 1e-10).unwrap();
    println!("indep exact {:?}\n spec {:?}", ex, sp);
    println!("{:#?}", m.modes().unwrap());
    println!("{:#?}", quarter_car(&q).modes().unwrap());
}
