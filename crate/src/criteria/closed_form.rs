//! Closed-form RMS criteria of the quarter car under white road velocity
//! (Gobbi and Mastinu 2001), valid for an undamped tyre (`ct = 0`):
//!
//! ```text
//! var(BAcc) = W (ks^2 (ms+mu) + cs^2 kt) / (2 cs ms^2)
//! var(SWS)  = W (ms+mu) / (2 cs)
//! var(DTL)  = W/(2 cs) [kt^2 mu + ((ms+mu)/ms)^2 (ks^2 (ms+mu) + cs^2 kt) - 2 ks kt mu (ms+mu)/ms]
//! ```
//! with `W = 2 pi^2 Gd(n0) n0^2 v` the intensity of the road velocity (m^2/s).

use crate::car::QuarterCar;
use crate::evaluate::Criteria;

/// RMS criteria of the quarter car `p` for road velocity intensity `w` (m^2/s).
/// Ignores `p.ct` (the formulas are for `ct = 0`).
pub fn quarter_car_rms(p: &QuarterCar, w: f64) -> Criteria {
    let QuarterCar {
        ms, mu, ks, cs, kt, ..
    } = *p;
    let m = ms + mu;
    let s = ks * ks * m + cs * cs * kt;
    let var_bacc = w * s / (2.0 * cs * ms * ms);
    let var_sws = w * m / (2.0 * cs);
    let r = m / ms;
    let var_dtl = w / (2.0 * cs) * (kt * kt * mu + r * r * s - 2.0 * ks * kt * mu * r);
    Criteria {
        bacc: var_bacc.sqrt(),
        dtl: var_dtl.sqrt(),
        sws: var_sws.sqrt(),
    }
}
