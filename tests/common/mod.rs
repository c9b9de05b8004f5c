//! Cars the HiFi route tests share.

use ridelab::car::Car;

/// A front-rear symmetric car (`a = b`, equal axles, `Iyy = M a^2`) at its own design:
/// heave and pitch, and the in-phase and anti-phase wheel hops, share their eigenvalues,
/// so `D(s)` has double roots; the residue route cannot resolve them and must fall back.
pub fn twin_axle_car() -> Car {
    let mut car = Car::datum();
    car.a = 1.4;
    car.b = 1.4;
    car.pitch_inertia = car.sprung_mass * 1.4 * 1.4;
    car.rear = car.front;
    car
}
