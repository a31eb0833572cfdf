//! The glyph sheet: one cell per glyph with its label, metric guides and advance box.
//!
//! Cells are square, `cell_px` wide, laid out `columns` per row, in code-point order
//! (glyphs without a code point after, by name). Every cell uses one scale, so glyphs
//! compare by size: the em (ascender to descender, stretched to the highest and lowest ink
//! of the font, e.g. accents on capitals) fills the glyph area, narrowed if the widest
//! advance would not fit. Ink beyond the cell sideways is clipped. The label (glyph name and
//! `U+XXXX`) is set in the font's own glyphs (`.notdef` or a box for characters it lacks),
//! shrunk to fit the cell width.

use kurbo::Point;
use tiny_skia::{Color, Pixmap, PixmapPaint, Transform};

use super::draw::{fill_glyph, line_px, rgb, stroke_glyph, Placement};
use super::{overlay, white_pixmap, RenderError, MAX_SIDE};
use crate::layout::Layout;
use crate::outline::OutlinedFont;

/// How to draw the sheet.
#[derive(Clone, Debug, PartialEq)]
pub struct SheetOptions {
    /// Side of a square cell, pixels (32..=2048).
    pub cell_px: u32,
    /// Cells per row (at least 1; fewer when the font has fewer glyphs, more when the sheet
    /// would be taller than [`MAX_SIDE`](super::MAX_SIDE)).
    pub columns: u32,
    /// Draw the X-spline control polygons and points and the Bézier on-curve points.
    pub overlay: bool,
}

impl Default for SheetOptions {
    fn default() -> Self {
        SheetOptions {
            cell_px: 160,
            columns: 8,
            overlay: false,
        }
    }
}

/// Colours of the guides (light, so the glyph reads first).
const ASC_DESC: [u8; 3] = [200, 200, 200];
const CAP: [u8; 3] = [130, 175, 235];
const XHEIGHT: [u8; 3] = [120, 205, 140];
const BASELINE: [u8; 3] = [110, 110, 110];
const ADVANCE: [u8; 3] = [235, 140, 140];
const GRID: [u8; 3] = [215, 215, 215];
const LABEL: [u8; 3] = [70, 70, 70];
/// The glyph in overlay mode: grey, so the points on top stay readable.
const GLYPH_UNDER_OVERLAY: [u8; 3] = [185, 185, 185];
/// The exported Bézier outline in overlay mode.
const OUTLINE_UNDER_OVERLAY: [u8; 3] = [60, 60, 60];

/// Glyph indices in sheet order: by lowest code point, then unencoded glyphs by name.
pub fn sheet_order(font: &OutlinedFont) -> Vec<usize> {
    let mut encoded: Vec<(char, usize)> = Vec::new();
    let mut unencoded: Vec<(&str, usize)> = Vec::new();
    for (i, g) in font.glyphs.iter().enumerate() {
        match g.unicodes.iter().min() {
            Some(&c) => encoded.push((c, i)),
            None => unencoded.push((g.name.as_str(), i)),
        }
    }
    encoded.sort();
    unencoded.sort();
    encoded
        .into_iter()
        .map(|(_, i)| i)
        .chain(unencoded.into_iter().map(|(_, i)| i))
        .collect()
}

/// The label of a glyph: its name and its lowest code point.
pub fn label(name: &str, unicodes: &[char]) -> String {
    match unicodes.iter().min() {
        Some(&c) => format!("{name} U+{:04X}", u32::from(c)),
        None => name.to_string(),
    }
}

/// Renders the sheet for every glyph of `font`.
pub fn render_sheet(font: &OutlinedFont, opts: &SheetOptions) -> Result<Pixmap, RenderError> {
    if !(32..=2048).contains(&opts.cell_px) {
        return Err(RenderError::Option(format!(
            "cell size {} px is out of range 32..=2048",
            opts.cell_px
        )));
    }
    if opts.columns == 0 {
        return Err(RenderError::Option("columns must be at least 1".into()));
    }
    let order = sheet_order(font);
    if order.is_empty() {
        return Err(RenderError::NoGlyphs);
    }
    let n = order.len() as u64;
    let cell = u64::from(opts.cell_px);
    // More columns than asked when the rows would be taller than an image can be.
    let max_rows = u64::from(MAX_SIDE) / cell;
    let columns = u64::from(opts.columns).max(n.div_ceil(max_rows)).min(n);
    let rows = n.div_ceil(columns);
    let mut sheet = white_pixmap(columns * cell, rows * cell)?;
    let geometry = CellGeometry::new(font, opts.cell_px);
    let layout = Layout::new(font);
    for (k, &index) in order.iter().enumerate() {
        let k = k as u64;
        let img = render_cell(font, &layout, &geometry, index, opts)?;
        sheet.draw_pixmap(
            ((k % columns) * cell) as i32,
            ((k / columns) * cell) as i32,
            img.as_ref(),
            &PixmapPaint::default(),
            Transform::identity(),
            None,
        );
    }
    Ok(sheet)
}

/// Sizes shared by all cells, pixels.
struct CellGeometry {
    cell: f64,
    pad: f64,
    /// Nominal label em height.
    label_em: f64,
    /// Pixels per font unit in the glyph area.
    scale: f64,
    /// Baseline of the glyph area.
    baseline: f64,
}

impl CellGeometry {
    fn new(font: &OutlinedFont, cell_px: u32) -> Self {
        let cell = f64::from(cell_px);
        let pad = (cell / 32.0).round().max(2.0);
        let label_em = (cell * 0.15).round();
        let (mut high, mut low) = (font.info.ascender, font.info.descender);
        if let Some(ink) = font.ink_bounds() {
            high = high.max(ink.y1);
            low = low.min(ink.y0);
        }
        let em = high - low;
        let widest = font.glyphs.iter().map(|g| g.advance).fold(em, f64::max);
        let top = pad + label_em + pad;
        let height = cell - top - pad;
        let scale = (height / em).min((cell - 2.0 * pad) / widest);
        CellGeometry {
            cell,
            pad,
            label_em,
            scale,
            baseline: top + high * scale,
        }
    }
}

fn render_cell(
    font: &OutlinedFont,
    layout: &Layout<'_>,
    geo: &CellGeometry,
    index: usize,
    opts: &SheetOptions,
) -> Result<Pixmap, RenderError> {
    let glyph = &font.glyphs[index];
    let mut img = white_pixmap(u64::from(opts.cell_px), u64::from(opts.cell_px))?;
    let at = Placement {
        scale: geo.scale,
        origin_x: ((geo.cell - glyph.advance * geo.scale) / 2.0).round(),
        baseline_y: geo.baseline.round(),
    };
    let info = &font.info;
    let (left, right) = (geo.pad, geo.cell - geo.pad);
    for (y, color) in [
        (info.ascender, ASC_DESC),
        (info.descender, ASC_DESC),
        (info.cap_height, CAP),
        (info.x_height, XHEIGHT),
        (0.0, BASELINE),
    ] {
        let py = at.snap_y(y);
        line_px(
            &mut img,
            Point::new(left, py),
            Point::new(right, py),
            rgb(color),
        );
    }
    let (top, bottom) = (at.snap_y(info.ascender), at.snap_y(info.descender));
    for x in [0.0, glyph.advance] {
        let px = at.snap_x(x);
        line_px(
            &mut img,
            Point::new(px, top),
            Point::new(px, bottom),
            rgb(ADVANCE),
        );
    }
    let ink = if opts.overlay {
        rgb(GLYPH_UNDER_OVERLAY)
    } else {
        Color::BLACK
    };
    fill_glyph(&mut img, &glyph.path, at, ink);
    if opts.overlay {
        stroke_glyph(&mut img, &glyph.path, at, rgb(OUTLINE_UNDER_OVERLAY));
        overlay::draw(&mut img, glyph, at, geo.cell);
    }
    draw_label(&mut img, font, layout, geo, index);
    // Grid: right and bottom edges, so neighbouring cells share one line.
    let edge = geo.cell - 0.5;
    line_px(
        &mut img,
        Point::new(edge, 0.0),
        Point::new(edge, geo.cell),
        rgb(GRID),
    );
    line_px(
        &mut img,
        Point::new(0.0, edge),
        Point::new(geo.cell, edge),
        rgb(GRID),
    );
    Ok(img)
}

fn draw_label(
    img: &mut Pixmap,
    font: &OutlinedFont,
    layout: &Layout<'_>,
    geo: &CellGeometry,
    index: usize,
) {
    let glyph = &font.glyphs[index];
    let line = layout.line(&label(&glyph.name, &glyph.unicodes));
    let em = font.info.ascender - font.info.descender;
    let mut scale = geo.label_em / em;
    let room = geo.cell - 2.0 * geo.pad;
    if line.width * scale > room {
        scale = room / line.width;
    }
    for placed in &line.glyphs {
        let at = Placement {
            scale,
            origin_x: geo.pad + placed.x * scale,
            baseline_y: geo.pad + font.info.ascender * scale,
        };
        fill_glyph(img, &layout.outline(placed).path, at, rgb(LABEL));
    }
}
