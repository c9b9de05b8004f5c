use ridelab::criteria::*;
use ridelab::model::*;
use ridelab::*;
fn main() {
    let car = Car::datum();
    let road = Road::default();
    let m = full_car(&car);
    let h = symmetric_half(&m);
    let ex = criteria_exact(&m, &road).unwrap();
    let exh = criteria_exact(&h, &road).unwrap();
    let t = std::time::Instant::now();
    for _ in 0..1000 {
        criteria_modal(&m, &road).unwrap();
    }
    println!("modal14 {:?}", t.elapsed() / 1000);
    let t = std::time::Instant::now();
    for _ in 0..1000 {
        criteria_modal(&h, &road).unwrap();
    }
    println!("modal8 {:?}", t.elapsed() / 1000);
    println!(
        "ex {:?}\nexh {:?}\nmod {:?}\nmodh {:?}",
        ex,
        exh,
        criteria_modal(&m, &road),
        criteria_modal(&h, &road)
    );
    let road2 = Road {
        tracks: Tracks::Independent,
        ..road
    };
    println!(
        "indep ex {:?}\n mod {:?}",
        criteria_exact(&m, &road2),
        criteria_modal(&m, &road2)
    );
}
