use ridelab::gpu::{MapInput, GpuMapper};
use ridelab::maps::{evaluate_grid, Grid};
use ridelab::design::DesignBox;
use ridelab::{Car, HiFi, Road, RoadClass, Tracks, Criteria};

fn cases() -> Vec<(String, Car, Tracks, DesignBox)> {
    let datum = Car::datum();
    let b = DesignBox::default();
    let mut heavy = datum.clone();
    heavy.front.unsprung_mass = 80.0;
    heavy.rear.unsprung_mass = 70.0;
    let mut ct = datum.clone();
    ct.front.tire_damping = 500.0;
    ct.rear.tire_damping = 500.0;
    let mut warp = datum.clone();
    warp.track_front = 1.522;
    warp.track_rear = 1.510;
    let low = DesignBox { cs_max: 1000.0, ..b };
    vec![
        ("datum".into(), datum.clone(), Tracks::Correlated, b),
        ("low cs".into(), datum.clone(), Tracks::Correlated, low),
        ("heavy".into(), heavy.clone(), Tracks::Correlated, b),
        ("heavy low".into(), heavy.clone(), Tracks::Independent, low),
        ("ct".into(), ct, Tracks::Correlated, b),
        ("indep".into(), datum.clone(), Tracks::Independent, b),
        ("warp".into(), warp.clone(), Tracks::Independent, b),
        ("warp low".into(), warp, Tracks::Independent, low),
        ("suv".into(), Car::preset("suv").unwrap(), Tracks::Independent, b),
        ("compact".into(), Car::preset("compact").unwrap(), Tracks::Correlated, low),
    ]
}

fn max_rel(a: &[Criteria], b: &[Criteria]) -> f64 {
    a.iter().zip(b).flat_map(|(x, y)| {
        x.to_array().into_iter().zip(y.to_array()).map(|(p, q)| (p / q - 1.0).abs())
    }).fold(0.0, f64::max)
}

#[test]
fn explore() {
    let mut k = 0;
    let t0 = std::time::Instant::now();
    let gpu = GpuMapper::new().unwrap();
    println!("adapter {:?} in {:?}", gpu.as_ref().map(|g| g.adapter_name().to_string()), t0.elapsed());
    for (name, car, tracks, b) in cases() {
        for speed in [5.0, 10.0, 20.0, 40.0] {
            let road = Road { class: RoadClass::ALL[k % 8], speed, tracks };
            k += 1;
            let grid = Grid::over_box(&b, 20, 20).unwrap();
            let hifi = HiFi::new(&car, &road).unwrap();
            let cpu = evaluate_grid(&hifi, &grid, 2).unwrap();
            let inp = MapInput::new(&car, &road, &grid).unwrap();
            let r64 = inp.map_cpu::<f64>().unwrap();
            let r32 = inp.map_cpu::<f32>().unwrap();
            let t0 = std::time::Instant::now();
            let rg = gpu.as_ref().map(|g| g.map(&inp).unwrap());
            let tg = t0.elapsed();
            if let Some(rg) = &rg { println!("   gpu {:.2e} vs cpu, {:.2e} vs f32 emu, {:?}", max_rel(rg, &cpu), max_rel(rg, &r32), tg); }
            println!("{name:10} v {speed:4} nodes {:4} ({} comb) cut {:?}  f64 {:.2e}  f32 {:.2e}",
                inp.rule.len(), inp.rule.combined.len(), inp.low_cutoff_hz, max_rel(&r64, &cpu), max_rel(&r32, &cpu));
        }
    }
}
