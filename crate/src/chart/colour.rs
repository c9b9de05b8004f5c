//! Colours: `#rrggbb` strings and the colour maps of the design maps.
//!
//! A colour map turns `t` in `[0, 1]` into one of 256 colours: `k = round(255 t)` (clamped),
//! then linear interpolation between the map's stops at `k / 255`, each channel rounded.
//! The page takes its tables from here (the wasm `colourTable`), so a map on screen and
//! its export have the same colours.

use crate::error::{Result, RideError};
use plotters::style::RGBColor;
use serde::{Deserialize, Serialize};

/// An sRGB colour, 8 bits a channel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Rgb(pub u8, pub u8, pub u8);

impl Rgb {
    /// Parses `#rrggbb` (hex digits of either case); errors name `field`.
    pub fn parse(field: &str, text: &str) -> Result<Rgb> {
        let bad = || {
            RideError::field(
                field,
                format!("'{text}' is not a colour of the form #rrggbb"),
            )
        };
        let hex = text.strip_prefix('#').ok_or_else(bad)?;
        if hex.len() != 6 || !hex.chars().all(|c| c.is_ascii_hexdigit()) {
            return Err(bad());
        }
        let channel = |k: usize| u8::from_str_radix(&hex[k..k + 2], 16).map_err(|_| bad());
        Ok(Rgb(channel(0)?, channel(2)?, channel(4)?))
    }

    /// `#RRGGBB`, upper case (the form the SVG backend writes).
    #[cfg(test)]
    pub(crate) fn hex(self) -> String {
        format!("#{:02X}{:02X}{:02X}", self.0, self.1, self.2)
    }

    /// `(1 - a) self + a other`, each channel rounded.
    pub(crate) fn mix(self, other: Rgb, a: f64) -> Rgb {
        let m = |x: u8, y: u8| ((1.0 - a) * f64::from(x) + a * f64::from(y)).round() as u8;
        Rgb(m(self.0, other.0), m(self.1, other.1), m(self.2, other.2))
    }

    pub(crate) fn plotters(self) -> RGBColor {
        RGBColor(self.0, self.1, self.2)
    }
}

/// Colour of a value that has none (not finite): the page's light grey.
const NO_VALUE: Rgb = Rgb(200, 200, 200);

/// The colour map of a [`super::MapChart`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ColourMap {
    /// Viridis (perceptually uniform, colour-blind safe), for absolute values.
    #[default]
    Viridis,
    /// Cividis (Nuñez, Anderton and Renslow 2018): blue to yellow with a lightness that
    /// rises steadily, made to look the same with red-green colour-vision deficiency; the
    /// page's colour-blind option for absolute values.
    Cividis,
    /// Blue (below zero: better than the datum) through white (zero) to red (worse);
    /// its colour range is made symmetric about zero.
    Diverging,
}

type Stops = &'static [(f64, [u8; 3])];

const VIRIDIS: Stops = &[
    (0.0, [68, 1, 84]),
    (0.125, [72, 40, 120]),
    (0.25, [62, 73, 137]),
    (0.375, [49, 104, 142]),
    (0.5, [38, 130, 142]),
    (0.625, [31, 158, 137]),
    (0.75, [53, 183, 121]),
    (0.875, [110, 206, 88]),
    (1.0, [253, 231, 37]),
];

/// Cividis sampled at six stops (its lightness is nearly linear, so six suffice).
const CIVIDIS: Stops = &[
    (0.0, [0, 34, 78]),
    (0.2, [53, 69, 108]),
    (0.4, [102, 105, 112]),
    (0.6, [148, 142, 119]),
    (0.8, [200, 184, 102]),
    (1.0, [254, 232, 56]),
];

const DIVERGING: Stops = &[
    (0.0, [33, 102, 172]),
    (0.25, [103, 169, 207]),
    (0.5, [247, 247, 247]),
    (0.75, [239, 138, 98]),
    (1.0, [178, 24, 43]),
];

impl ColourMap {
    fn stops(self) -> Stops {
        match self {
            ColourMap::Viridis => VIRIDIS,
            ColourMap::Cividis => CIVIDIS,
            ColourMap::Diverging => DIVERGING,
        }
    }

    /// Table entry `k` in `0..=255`.
    pub fn entry(self, k: u8) -> Rgb {
        let stops = self.stops();
        let t = f64::from(k) / 255.0;
        let mut s = 0;
        while s < stops.len() - 2 && t > stops[s + 1].0 {
            s += 1;
        }
        let ((t0, c0), (t1, c1)) = (stops[s], stops[s + 1]);
        let u = ((t - t0) / (t1 - t0)).clamp(0.0, 1.0);
        let ch =
            |c: usize| (f64::from(c0[c]) + u * (f64::from(c1[c]) - f64::from(c0[c]))).round() as u8;
        Rgb(ch(0), ch(1), ch(2))
    }

    /// The colour of `t` (0 at the low end of the colour range, 1 at the high end;
    /// clamped); [`NO_VALUE`] when `t` is not finite.
    pub fn colour(self, t: f64) -> Rgb {
        if !t.is_finite() {
            return NO_VALUE;
        }
        self.entry((t.clamp(0.0, 1.0) * 255.0).round() as u8)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_hex_colours_and_names_the_field() {
        assert_eq!(Rgb::parse("c", "#1d4ED8").unwrap(), Rgb(0x1d, 0x4e, 0xd8));
        assert_eq!(Rgb(0x1d, 0x4e, 0xd8).hex(), "#1D4ED8");
        for bad in [
            "1d4ed8",
            "#1d4ed",
            "#1d4ed8ff",
            "#gg0000",
            "red",
            "",
            "#1d4éd8",
        ] {
            let e = Rgb::parse("series[2].colour", bad).unwrap_err().to_string();
            assert!(e.starts_with("series[2].colour: "), "{bad}: {e}");
        }
    }

    #[test]
    fn maps_interpolate_their_stops() {
        // The stops at their exact entries and hand-interpolated ones between.
        let v = ColourMap::Viridis;
        assert_eq!(v.colour(0.0), Rgb(68, 1, 84));
        assert_eq!(v.colour(1.0), Rgb(253, 231, 37));
        assert_eq!(v.colour(-3.0), Rgb(68, 1, 84));
        assert_eq!(v.colour(7.0), Rgb(253, 231, 37));
        // k = 128: t = 0.50196, between 0.5 and 0.625, u = 0.015686:
        // (38 - 7 u, 130 + 28 u, 142 - 5 u) = (37.89, 130.44, 141.92).
        assert_eq!(v.colour(0.5), Rgb(38, 130, 142));
        // k = 64: t = 0.25098, u = 0.0078431 after 0.25: (62 - 13 u, 73 + 31 u, 137 + 5 u).
        assert_eq!(v.colour(0.25), Rgb(62, 73, 137));
        let d = ColourMap::Diverging;
        // t = 0.5 is entry 128, a hair past the white stop: 247 + 0.00784 (138 - 247).
        assert_eq!(d.colour(0.5), Rgb(247, 246, 246));
        assert_eq!(d.entry(127), Rgb(246, 246, 247));
        assert_eq!(d.colour(0.0), Rgb(33, 102, 172));
        assert_eq!(d.colour(1.0), Rgb(178, 24, 43));
        assert_eq!(d.colour(f64::NAN), NO_VALUE);
        // Mid-way between stops 0 and 0.25: k = 32, t = 0.12549, u = 0.50196.
        let u = 32.0 / 255.0 / 0.25;
        let expect = |a: f64, b: f64| (a + u * (b - a)).round() as u8;
        assert_eq!(
            d.colour(32.0 / 255.0),
            Rgb(
                expect(33.0, 103.0),
                expect(102.0, 169.0),
                expect(172.0, 207.0)
            )
        );
    }

    #[test]
    fn cividis_runs_dark_blue_to_yellow_with_rising_lightness() {
        let c = ColourMap::Cividis;
        assert_eq!(c.entry(0), Rgb(0, 34, 78));
        assert_eq!(c.entry(255), Rgb(254, 232, 56));
        // k = 51: t = 0.2 exactly, the second stop.
        assert_eq!(c.entry(51), Rgb(53, 69, 108));
        // Relative luminance (Rec. 709 weights on the 8-bit channels) never falls.
        let lum = |k: u8| {
            let Rgb(r, g, b) = c.entry(k);
            0.2126 * f64::from(r) + 0.7152 * f64::from(g) + 0.0722 * f64::from(b)
        };
        for k in 1..=255u8 {
            assert!(lum(k) >= lum(k - 1), "lightness falls at entry {k}");
        }
    }

    #[test]
    fn mixes_channels() {
        assert_eq!(
            Rgb(0, 100, 200).mix(Rgb(150, 150, 150), 0.62),
            Rgb(93, 131, 169)
        );
    }
}
