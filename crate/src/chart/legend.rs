//! The legend box shared by the line and map charts: a translucent white box in one corner
//! of the plot with one row per entry, a sample (drawn by the caller) and its name. Text
//! is measured by the backend, never by plotters' own legend, which measures text in the
//! document on wasm (a `<span>` per label) and so fails in a Web Worker and differs from
//! the native layout.

use super::draw::{self, drawing_error, font, Area};
use super::marker::Legend;
use super::Frame;
use crate::error::Result;
use plotters::backend::DrawingBackend;
use plotters::element::Rectangle;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{Color, RGBColor, ShapeStyle, WHITE};

/// Legend geometry, px: gap to the frame, padding, row height, sample width, gap to text.
const LEGEND: (i32, i32, i32, i32, i32) = (8, 6, 18, 22, 6);

/// Where one row's sample goes: from `left` to `left + width`, centred at `(centre, y)`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Row {
    pub left: i32,
    pub width: i32,
    pub centre: i32,
    pub y: i32,
}

/// Draws the box and the `names` in `corner` of `frame` and returns each row's sample
/// place; nothing (and no rows) when `corner` is [`Legend::None`] or `names` is empty.
pub(crate) fn legend_box<DB: DrawingBackend>(
    root: &Area<DB>,
    corner: Legend,
    frame: &Frame,
    names: &[&str],
) -> Result<Vec<Row>> {
    if names.is_empty() || corner == Legend::None {
        return Ok(Vec::new());
    }
    let (gap, pad, row, sample, text_gap) = LEGEND;
    let style = font(draw::LABEL_PX, false);
    let mut text_w = 0;
    for name in names {
        let (w, _) = root
            .estimate_text_size(name, &style)
            .map_err(drawing_error)?;
        text_w = text_w.max(w as i32);
    }
    let w = pad + sample + text_gap + text_w + pad;
    let h = pad + row * names.len() as i32 + pad / 2;
    let x0 = match corner {
        Legend::UpperLeft | Legend::LowerLeft => frame.left + gap,
        _ => frame.right - gap - w,
    };
    let y0 = match corner {
        Legend::LowerLeft | Legend::LowerRight => frame.bottom - gap - h,
        _ => frame.top + gap,
    };
    root.draw(&Rectangle::new(
        [(x0, y0), (x0 + w, y0 + h)],
        WHITE.mix(0.88).filled(),
    ))
    .map_err(drawing_error)?;
    root.draw(&Rectangle::new(
        [(x0, y0), (x0 + w, y0 + h)],
        ShapeStyle::from(RGBColor(187, 187, 187)).stroke_width(1),
    ))
    .map_err(drawing_error)?;
    let text = style.pos(Pos::new(HPos::Left, VPos::Center));
    let mut rows = Vec::with_capacity(names.len());
    for (i, name) in names.iter().enumerate() {
        let y = y0 + pad + row * i as i32 + row / 2;
        let left = x0 + pad;
        root.draw_text(name, &text, (left + sample + text_gap, y))
            .map_err(drawing_error)?;
        rows.push(Row {
            left,
            width: sample,
            centre: left + sample / 2,
            y,
        });
    }
    Ok(rows)
}
