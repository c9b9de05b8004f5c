//! Writes the synthetic example road profiles into `assets/roads/`
//! (`ridelab::road_profile::shipped_examples`), and says what `describe` makes of them.
//!
//! Run: `cargo run -p ridelab --example make_road_profiles`.

use ridelab::road_profile::{describe, shipped_examples, synthesize, EXAMPLE_DECIMALS};
use std::path::Path;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/roads");
    std::fs::create_dir_all(&dir)?;
    for (name, settings) in shipped_examples() {
        let profile = synthesize(&settings)?;
        let text = profile.to_csv(EXAMPLE_DECIMALS.0, EXAMPLE_DECIMALS.1);
        let path = dir.join(name);
        std::fs::write(&path, &text)?;
        let d = describe(&profile)?;
        println!(
            "{} ({} bytes, {} samples, {} track(s)): class {:?}, Gd(n0) {:.3e} m^3, waviness {:.2}, residual {:.3}",
            path.display(),
            text.len(),
            profile.len(),
            profile.tracks(),
            d.iso8608.class,
            d.iso8608.gd_n0,
            d.iso8608.waviness,
            d.iso8608.residual
        );
    }
    Ok(())
}
