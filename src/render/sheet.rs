//! The glyph sheet: one cell per glyph with its label, metric guides and advance box.
//!
//! Cells are square, `cell_px` wide, laid out `columns` per row, in code-point order
//! (glyphs without a code point after, by name). Every cell uses one scale, so glyphs
//! compare by size: the em (ascender to descender, stretched to the highest and lowest ink
//! of the font, e.g. accents on capitals) fills the glyph area, narrowed if the widest
//! advance would not fit. Ink beyond the cell sideways is clipped. The label (glyph name and
//! `U+XXXX`) is set in the font's own glyphs when it has them all, else in the built-in
//! [`labels`] face; it is shrunk to fit the cell width.
//!
//! A large font is cut into pages ([`sheet_pages`]) of at most [`PAGE_ROWS`] rows, each
//! page within the image limits, so thousands of glyphs give `sheet-1.png`, `sheet-2.png`, …
//! rather than one image taller than a PNG viewer (or [`MAX_SIDE`]) allows.

use std::path::Path;
use std::sync::Mutex;

use kurbo::Point;
use rayon::prelude::*;
use tiny_skia::{Color, Pixmap, PixmapMut};

use super::draw::{fill_glyph, line_px, put_opaque, rgb, stroke_glyph, Placement};
use super::{labels, overlay, white_pixmap_in, RenderError, MAX_AREA, MAX_SIDE};
use crate::layout::Layout;
use crate::outline::OutlinedFont;
use crate::reuse::{glyph_key, Key, KeyBuilder, OutlineKeys, Reuse};

/// How to draw the sheet.
#[derive(Clone, Debug, PartialEq)]
pub struct SheetOptions {
    /// Side of a square cell, pixels (32..=2048).
    pub cell_px: u32,
    /// Cells per row (at least 1; fewer when the font has fewer glyphs, more when the sheet
    /// would be taller than [`MAX_SIDE`]).
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

/// Rows of cells on one sheet page at most (512 glyphs a page at the default 8 columns).
pub const PAGE_ROWS: u64 = 64;

/// The sheet order cut into pages: each page `columns` cells wide (fewer when the font has
/// fewer glyphs) and at most [`PAGE_ROWS`] rows tall (fewer when taller or larger than the
/// image limits). One page when the font fits on it. Columns wider than an image can be are
/// not narrowed: rendering the page then fails with [`RenderError::Size`], which names them.
pub fn sheet_pages(
    font: &OutlinedFont,
    opts: &SheetOptions,
) -> Result<Vec<Vec<usize>>, RenderError> {
    check_options(opts)?;
    let order = sheet_order(font);
    if order.is_empty() {
        return Err(RenderError::NoGlyphs);
    }
    let cell = u64::from(opts.cell_px);
    let max_cells = u64::from(MAX_SIDE) / cell;
    let columns = u64::from(opts.columns);
    let rows = PAGE_ROWS
        .min(max_cells)
        .min(MAX_AREA / (columns * cell * cell))
        .max(1);
    let per_page = (columns * rows) as usize;
    Ok(order.chunks(per_page).map(<[usize]>::to_vec).collect())
}

/// File names of `pages` sheet pages: `{stem}.png` for one, else `{stem}-1.png`, ….
pub fn page_file_names(stem: &str, pages: usize) -> Vec<String> {
    match pages {
        1 => vec![format!("{stem}.png")],
        n => (1..=n).map(|k| format!("{stem}-{k}.png")).collect(),
    }
}

/// Every sheet page as PNG bytes, named by [`page_file_names`] from `stem` (`"sheet"`).
/// Pages are rendered in parallel (rayon); the bytes do not depend on the thread count.
pub fn sheet_png_files(
    font: &OutlinedFont,
    opts: &SheetOptions,
    stem: &str,
) -> Result<Vec<(String, Vec<u8>)>, RenderError> {
    sheet_png_files_with(&Layout::new(font)?, opts, stem)
}

/// [`sheet_png_files`] with a shaper already built (its TTF built once for every page, and
/// for the proof too: [`Layout::with_ttf`]).
pub fn sheet_png_files_with(
    layout: &Layout<'_>,
    opts: &SheetOptions,
    stem: &str,
) -> Result<Vec<(String, Vec<u8>)>, RenderError> {
    sheet_png_files_reusing(
        layout,
        opts,
        stem,
        &Reuse::off(),
        None,
        &OutlineKeys::default(),
    )
}

/// [`sheet_png_files_with`], taking from OUT each page whose inputs did not change since the
/// last build ([`Reuse`]). `font_key` is [`crate::reuse::font_key`] of the layout's font
/// and TTF; a page whose labels are set in the font's own glyphs depends on it (without
/// it such a page is always drawn), a page of built-in labels only on its own glyphs.
/// `outlines` are the font's [`OutlineKeys`].
pub fn sheet_png_files_reusing(
    layout: &Layout<'_>,
    opts: &SheetOptions,
    stem: &str,
    reuse: &Reuse,
    font_key: Option<&Key>,
    outlines: &OutlineKeys,
) -> Result<Vec<(String, Vec<u8>)>, RenderError> {
    let pages = sheet_pages(layout.font(), opts)?;
    let names = page_file_names(stem, pages.len());
    // One scale for every page (the whole font's ink), computed once.
    let geometry = CellGeometry::new(layout.font(), opts.cell_px);
    // The memory of pages already encoded, for the next pages (at most one per core).
    let spare: Mutex<Vec<Vec<u8>>> = Mutex::new(Vec::new());
    names
        .into_par_iter()
        .zip(pages.par_iter())
        // One page per job: rayon's pieces otherwise end in a run of pages on one core
        // while the other waits (a CJK font's last 10 pages, 1.5 s).
        .with_max_len(1)
        .map(|(name, order)| {
            let draw = || {
                let memory = spare.lock().ok().and_then(|mut s| s.pop());
                let page = render_page(layout, &geometry, opts, order, memory.unwrap_or_default())?;
                let png = super::encode_png(&page);
                if let Ok(mut s) = spare.lock() {
                    s.push(page.take());
                }
                png
            };
            let png = match page_key(layout, &geometry, opts, &name, order, font_key, outlines) {
                Some(key) => reuse.get_or_make(Path::new(&name), key, draw)?,
                None => draw()?,
            };
            Ok((name, png))
        })
        .collect()
}

/// What a sheet page's pixels depend on; `None` when its labels use the font and no
/// `font_key` is given.
fn page_key(
    layout: &Layout<'_>,
    geo: &CellGeometry,
    opts: &SheetOptions,
    name: &str,
    order: &[usize],
    font_key: Option<&Key>,
    outlines: &OutlineKeys,
) -> Option<Key> {
    let font = layout.font();
    let info = &font.info;
    let mut k = KeyBuilder::new("sheet page");
    k.str(name)
        .str(&format!("{opts:?}"))
        .f64(geo.cell)
        .f64(geo.pad)
        .f64(geo.label_em)
        .f64(geo.scale)
        .f64(geo.baseline);
    for v in [
        info.ascender,
        info.descender,
        info.cap_height,
        info.x_height,
    ] {
        k.f64(v);
    }
    k.u64(order.len() as u64);
    let mut uses_font = false;
    for &i in order {
        let g = &font.glyphs[i];
        k.key(&glyph_key(g, &outlines.get(i, &g.path), opts.overlay));
        uses_font |= label(&g.name, &g.unicodes)
            .chars()
            .all(|c| layout.covers(c));
    }
    if uses_font {
        // The label is shaped on the TTF and drawn with the font's glyphs.
        k.key(font_key?);
    }
    Some(k.finish())
}

fn check_options(opts: &SheetOptions) -> Result<(), RenderError> {
    if !(32..=2048).contains(&opts.cell_px) {
        return Err(RenderError::Option(format!(
            "cell size {} px is out of range 32..=2048",
            opts.cell_px
        )));
    }
    if opts.columns == 0 {
        return Err(RenderError::Option("columns must be at least 1".into()));
    }
    Ok(())
}

/// Renders the sheet for every glyph of `font` as one image. A font too large for one
/// image fails with [`RenderError::Size`]: use [`sheet_pages`] and [`render_sheet_page`].
pub fn render_sheet(font: &OutlinedFont, opts: &SheetOptions) -> Result<Pixmap, RenderError> {
    check_options(opts)?;
    let order = sheet_order(font);
    if order.is_empty() {
        return Err(RenderError::NoGlyphs);
    }
    render_sheet_page(font, opts, &order)
}

/// Renders the cells of the glyphs `order` (indices into `font.glyphs`, one page of
/// [`sheet_pages`]) as one image.
pub fn render_sheet_page(
    font: &OutlinedFont,
    opts: &SheetOptions,
    order: &[usize],
) -> Result<Pixmap, RenderError> {
    render_sheet_page_with(&Layout::new(font)?, opts, order)
}

/// [`render_sheet_page`] with a shaper already built.
pub fn render_sheet_page_with(
    layout: &Layout<'_>,
    opts: &SheetOptions,
    order: &[usize],
) -> Result<Pixmap, RenderError> {
    check_options(opts)?;
    let geometry = CellGeometry::new(layout.font(), opts.cell_px);
    render_page(layout, &geometry, opts, order, Vec::new())
}

/// One page, drawn in the memory of `spare` ([`super::white_pixmap_in`]).
fn render_page(
    layout: &Layout<'_>,
    geometry: &CellGeometry,
    opts: &SheetOptions,
    order: &[usize],
    spare: Vec<u8>,
) -> Result<Pixmap, RenderError> {
    let font = layout.font();
    if order.is_empty() {
        return Err(RenderError::NoGlyphs);
    }
    let n = order.len() as u64;
    let cell = u64::from(opts.cell_px);
    // More columns than asked when the rows would be taller than an image can be.
    let max_rows = u64::from(MAX_SIDE) / cell;
    let columns = u64::from(opts.columns).max(n.div_ceil(max_rows)).min(n);
    let rows = n.div_ceil(columns);
    let width = columns * cell;
    let mut sheet = white_pixmap_in(spare, width, rows * cell)?;
    // Each row of cells a rayon job (an edited glyph's page is drawn on every core), its
    // cells drawn in turn in the memory of the one before; errors in cell order.
    let strip_bytes = (width * cell * 4) as usize;
    let drawn: Vec<Result<(), RenderError>> = sheet
        .data_mut()
        .par_chunks_mut(strip_bytes)
        .zip(order.par_chunks(columns as usize))
        .map(|(strip, row)| {
            let mut strip = PixmapMut::from_bytes(strip, width as u32, cell as u32).ok_or(
                RenderError::Size {
                    width,
                    height: cell,
                },
            )?;
            let mut memory = Vec::new();
            for (c, &index) in row.iter().enumerate() {
                let img = render_cell(font, layout, geometry, index, opts, memory)?;
                put_opaque(&mut strip, &img, c as u32 * cell as u32, 0);
                memory = img.take();
            }
            Ok(())
        })
        .collect();
    drawn.into_iter().collect::<Result<(), _>>()?;
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
    spare: Vec<u8>,
) -> Result<Pixmap, RenderError> {
    let glyph = &font.glyphs[index];
    let mut img = white_pixmap_in(spare, u64::from(opts.cell_px), u64::from(opts.cell_px))?;
    let mut canvas = img.as_mut();
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
            &mut canvas,
            Point::new(left, py),
            Point::new(right, py),
            rgb(color),
        );
    }
    let (top, bottom) = (at.snap_y(info.ascender), at.snap_y(info.descender));
    for x in [0.0, glyph.advance] {
        let px = at.snap_x(x);
        line_px(
            &mut canvas,
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
    fill_glyph(&mut canvas, &glyph.path, at, ink);
    if opts.overlay {
        stroke_glyph(&mut canvas, &glyph.path, at, rgb(OUTLINE_UNDER_OVERLAY));
        overlay::draw(&mut canvas, glyph, at, geo.cell);
    }
    draw_label(&mut canvas, font, layout, geo, index)?;
    // Grid: right and bottom edges, so neighbouring cells share one line.
    let edge = geo.cell - 0.5;
    line_px(
        &mut canvas,
        Point::new(edge, 0.0),
        Point::new(edge, geo.cell),
        rgb(GRID),
    );
    line_px(
        &mut canvas,
        Point::new(0.0, edge),
        Point::new(geo.cell, edge),
        rgb(GRID),
    );
    Ok(img)
}

fn draw_label(
    img: &mut PixmapMut<'_>,
    font: &OutlinedFont,
    layout: &Layout<'_>,
    geo: &CellGeometry,
    index: usize,
) -> Result<(), RenderError> {
    let glyph = &font.glyphs[index];
    let text = label(&glyph.name, &glyph.unicodes);
    if !text.chars().all(|c| layout.covers(c)) {
        let room = geo.cell - 2.0 * geo.pad;
        labels::draw_line(
            img,
            &text,
            (geo.pad, geo.pad),
            geo.label_em,
            room,
            rgb(LABEL),
        );
        return Ok(());
    }
    let line = layout.line(&text)?;
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
            baseline_y: geo.pad + (font.info.ascender - placed.y) * scale,
        };
        fill_glyph(img, &layout.outline(placed).path, at, rgb(LABEL));
    }
    Ok(())
}
