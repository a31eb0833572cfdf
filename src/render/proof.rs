//! The text proof: lines of text set in the font, at several sizes (a waterfall).
//!
//! Black text on white, shaped as a browser shapes it: kerning, ligatures and marks come
//! from the font's own TTF through HarfRust ([`crate::layout`]).
//! Sizes are pixels per em (`units_per_em` font units). Each size sets every line of the
//! text; the image is as wide as the longest line (plus margins) up to a maximum width,
//! and lines longer than that are cut at the right edge (no wrapping).

use std::collections::BTreeSet;
use std::ops::Range;

use tiny_skia::{Color, Pixmap, PixmapMut};

use super::draw::{fill_glyph, Placement};
use super::{white_pixmap, RenderError, MAX_AREA, MAX_SIDE};
use crate::layout::{Layout, Line};
use crate::outline::OutlinedFont;

/// How to set the proof.
#[derive(Clone, Debug, PartialEq)]
pub struct ProofOptions {
    /// The text; `None` picks [`default_text`]. `'\n'` separates lines.
    pub text: Option<String>,
    /// Pixels per em, one block per size, top to bottom (each 1..=1000).
    pub sizes: Vec<f64>,
    /// Largest image width, pixels; the image is as wide as its longest line plus margins,
    /// up to this (longer lines are cut).
    pub width_px: u32,
}

impl Default for ProofOptions {
    fn default() -> Self {
        ProofOptions {
            text: None,
            sizes: vec![12.0, 16.0, 24.0, 36.0, 48.0, 72.0],
            width_px: 1200,
        }
    }
}

/// Texts tried in order; each one the font covers fully becomes a proof line.
const CANDIDATES: &[&str] = &[
    "The quick brown fox jumps over the lazy dog.",
    "SPHINX OF BLACK QUARTZ, JUDGE MY VOW",
    "Hamburgefonstiv nonooonnoon HOHOOHHOOH",
    "0123456789 (1,234.56)",
    "AVATAR Tower LT Yo Wave Type P.A.W. \"F,\"",
    "Où est la forêt? Ça va, très bien! Äpfel, Öl, Übermut, Ñandú",
    // The Thousand Character Classic's first lines (simplified, then traditional), for
    // fonts of the CJK Unified Ideographs block; no punctuation, which such fonts may lack.
    "天地玄黄宇宙洪荒日月盈昃辰宿列张寒来暑往秋收冬藏",
    "天地玄黃宇宙洪荒日月盈昃辰宿列張寒來暑往秋收冬藏",
];

/// A text for the font: the candidate lines it covers; if it covers none, every character
/// it has (in code-point order, marks and spaces left out) followed by its kerning pairs.
pub fn default_text(font: &OutlinedFont) -> String {
    // The font's own code points (no shaper needed to pick the text).
    let covered: BTreeSet<char> = font
        .glyphs
        .iter()
        .flat_map(|g| g.unicodes.iter().copied())
        .collect();
    let lines: Vec<&str> = CANDIDATES
        .iter()
        .copied()
        .filter(|t| t.chars().all(|c| covered.contains(&c)))
        .collect();
    if !lines.is_empty() {
        return lines.join("\n");
    }
    let mut chars: Vec<char> = font
        .glyphs
        .iter()
        .filter(|g| g.advance > 0.0)
        .flat_map(|g| g.unicodes.iter().copied())
        .filter(|c| !c.is_whitespace() && !c.is_control())
        .collect();
    chars.sort_unstable();
    chars.dedup();
    let mut text: String = chars.into_iter().collect();
    let pairs: Vec<String> = font
        .kerning
        .iter()
        .filter_map(|k| {
            let l = font.glyph(&k.left)?.unicodes.iter().min()?;
            let r = font.glyph(&k.right)?.unicodes.iter().min()?;
            Some(format!("{l}{r}"))
        })
        .collect();
    if !pairs.is_empty() {
        text.push('\n');
        text.push_str(&pairs.join(" "));
    }
    text
}

/// Left and top margin, pixels.
const MARGIN: f64 = 16.0;

/// Renders the proof of `font`.
pub fn render_proof(font: &OutlinedFont, opts: &ProofOptions) -> Result<Pixmap, RenderError> {
    check_sizes(opts)?;
    proof_pixmap(&Layout::new(font)?, opts)
}

/// [`render_proof`] with a shaper already built, e.g. on a TTF the caller has
/// ([`Layout::with_ttf`]).
pub fn render_proof_with(layout: &Layout<'_>, opts: &ProofOptions) -> Result<Pixmap, RenderError> {
    check_sizes(opts)?;
    proof_pixmap(layout, opts)
}

/// At least one size, each 1..=1000 px per em.
fn check_sizes(opts: &ProofOptions) -> Result<(), RenderError> {
    if opts.sizes.is_empty() {
        return Err(RenderError::Option("at least one size is needed".into()));
    }
    if let Some(bad) = opts
        .sizes
        .iter()
        .find(|s| !(s.is_finite() && (1.0..=1000.0).contains(*s)))
    {
        return Err(RenderError::Option(format!(
            "size {bad} px is out of range 1..=1000"
        )));
    }
    Ok(())
}

fn proof_pixmap(layout: &Layout<'_>, opts: &ProofOptions) -> Result<Pixmap, RenderError> {
    let plan = ProofPlan::new(layout, opts)?;
    let mut img = white_pixmap(plan.width, plan.height)?;
    plan.draw(&mut img.as_mut(), layout);
    Ok(img)
}

/// Where a proof's glyphs go, worked out before a pixel is drawn, so that the instances
/// proof sizes one image for all its blocks and draws each block in its own rows.
struct ProofPlan {
    laid: Vec<Line>,
    /// Per size: pixels per font unit, and the baseline of each line.
    blocks: Vec<(f64, Vec<f64>)>,
    width: u64,
    height: u64,
}

impl ProofPlan {
    fn new(layout: &Layout<'_>, opts: &ProofOptions) -> Result<ProofPlan, RenderError> {
        let font = layout.font();
        let text = opts.text.clone().unwrap_or_else(|| default_text(font));
        let info = &font.info;
        let upm = f64::from(info.units_per_em);
        // Lines are spaced by the em box, widened to the font's ink (accented capitals
        // reach above the ascender), so no glyph is cut off or touches the next line.
        let (mut top, mut bottom) = (info.ascender, info.descender);
        if let Some(ink) = font.ink_bounds() {
            top = top.max(ink.y1);
            bottom = bottom.min(ink.y0);
        }
        let em = (info.ascender - info.descender).max(top - bottom);
        let laid = text
            .lines()
            .map(|l| layout.line(l))
            .collect::<Result<Vec<_>, _>>()?;
        let widest = laid.iter().map(|l| l.width).fold(0.0, f64::max);
        let mut y = MARGIN;
        let mut blocks = Vec::new();
        let mut width = 2.0 * MARGIN + 1.0;
        for &size in &opts.sizes {
            let scale = size / upm;
            width = width.max((2.0 * MARGIN + widest * scale).ceil());
            let leading = (em * scale * 1.2).ceil();
            let mut baselines = Vec::new();
            for _ in &laid {
                baselines.push((y + top * scale).round());
                y += leading;
            }
            blocks.push((scale, baselines));
            y += (size * 0.5).round();
        }
        Ok(ProofPlan {
            laid,
            blocks,
            width: (width as u64).min(u64::from(opts.width_px)),
            height: (y + MARGIN).ceil() as u64,
        })
    }

    /// Draws the glyphs onto `canvas`, whose top left is the plan's; glyphs whose origin
    /// is past the plan's width are skipped.
    fn draw(&self, canvas: &mut PixmapMut<'_>, layout: &Layout<'_>) {
        for (scale, baselines) in &self.blocks {
            for (line, baseline) in self.laid.iter().zip(baselines) {
                for placed in &line.glyphs {
                    let origin_x = MARGIN + placed.x * scale;
                    if origin_x > self.width as f64 {
                        break;
                    }
                    let at = Placement {
                        scale: *scale,
                        origin_x,
                        baseline_y: baseline - placed.y * scale,
                    };
                    fill_glyph(canvas, &layout.outline(placed).path, at, Color::BLACK);
                }
            }
        }
    }
}

/// Height of an instance label line, pixels per em of the built-in label face.
const LABEL_EM: f64 = 20.0;

/// The proof of several fonts (the named instances of a font with masters), stacked top to
/// bottom, each block under its label (set in the built-in face, [`super::labels`]). Every
/// block sets the same text: `opts.text`, or the first font's [`default_text`].
pub fn render_instances_proof(
    fonts: &[(String, &OutlinedFont)],
    opts: &ProofOptions,
) -> Result<Pixmap, RenderError> {
    let layouts = fonts
        .iter()
        .map(|(label, font)| Ok((label.clone(), Layout::new(font)?)))
        .collect::<Result<Vec<_>, RenderError>>()?;
    let layouts: Vec<(String, &Layout<'_>)> = layouts.iter().map(|(l, s)| (l.clone(), s)).collect();
    render_instances_proof_with(&layouts, opts)
}

/// [`render_instances_proof`] with each font's shaper already built, on one image (an
/// error when the blocks together exceed the image limits; [`InstancesProof::pages`]
/// splits them).
pub fn render_instances_proof_with(
    fonts: &[(String, &Layout<'_>)],
    opts: &ProofOptions,
) -> Result<Pixmap, RenderError> {
    InstancesProof::new(fonts, opts)?.render(0..fonts.len())
}

/// The instances proof laid out: one block per font, each under its label, ready to be
/// cut into pages within the image limits and drawn page by page.
pub struct InstancesProof<'f, 'l> {
    fonts: &'f [(String, &'f Layout<'l>)],
    plans: Vec<ProofPlan>,
    label_h: u64,
}

impl<'f, 'l> InstancesProof<'f, 'l> {
    /// Sets every block's text: `opts.text`, or the first font's [`default_text`], in
    /// parallel (rayon).
    pub fn new(
        fonts: &'f [(String, &'f Layout<'l>)],
        opts: &ProofOptions,
    ) -> Result<Self, RenderError> {
        use rayon::prelude::*;
        let Some((_, first)) = fonts.first() else {
            return Err(RenderError::NoGlyphs);
        };
        let opts = ProofOptions {
            text: Some(
                opts.text
                    .clone()
                    .unwrap_or_else(|| default_text(first.font())),
            ),
            ..opts.clone()
        };
        check_sizes(&opts)?;
        let plans = fonts
            .par_iter()
            .map(|(_, layout)| ProofPlan::new(layout, &opts))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(InstancesProof {
            fonts,
            plans,
            label_h: (LABEL_EM * 1.5).ceil() as u64,
        })
    }

    /// The blocks cut into pages, in order: as many blocks a page as stay within
    /// [`MAX_SIDE`] and [`MAX_AREA`] (one page when they all do). A block too large by
    /// itself gets a page of its own, which [`Self::render`] then refuses, naming its size.
    pub fn pages(&self) -> Vec<Range<usize>> {
        let width = self.width();
        let mut pages = Vec::new();
        let (mut start, mut height) = (0, 0u64);
        for (k, plan) in self.plans.iter().enumerate() {
            let block = self.label_h + plan.height;
            let fits = |h: u64| h <= u64::from(MAX_SIDE) && h * width <= MAX_AREA;
            if k > start && !fits(height + block) {
                pages.push(start..k);
                (start, height) = (k, 0);
            }
            height += block;
        }
        pages.push(start..self.plans.len());
        pages
    }

    /// Every page's width: the widest block's, so that pages line up.
    fn width(&self) -> u64 {
        self.plans.iter().map(|p| p.width).max().unwrap_or(1)
    }

    /// The blocks of `page` stacked top to bottom, each drawn in its own rows in parallel.
    pub fn render(&self, page: Range<usize>) -> Result<Pixmap, RenderError> {
        use rayon::prelude::*;
        let (plans, fonts) = (&self.plans[page.clone()], &self.fonts[page]);
        let label_h = self.label_h;
        let width = self.width();
        let height: u64 = plans.iter().map(|p| label_h + p.height).sum();
        // One image, each block drawn in its own rows in parallel: blocks drawn apart and
        // copied in touched twice the memory, each fresh page a page fault (the bundled
        // build's most: 56 % of its faults were this proof's white fill).
        let mut img = white_pixmap(width, height)?;
        let row_bytes = width as usize * 4;
        let mut rest = img.data_mut();
        let mut strips = Vec::with_capacity(plans.len());
        for plan in plans {
            let (_label, after) = rest.split_at_mut(label_h as usize * row_bytes);
            let (strip, after) = after.split_at_mut(plan.height as usize * row_bytes);
            strips.push(strip);
            rest = after;
        }
        strips
            .into_par_iter()
            .zip(plans.par_iter().zip(fonts.par_iter()))
            .map(|(strip, (plan, (_, layout)))| {
                let size = RenderError::Size {
                    width,
                    height: plan.height,
                };
                let mut canvas =
                    PixmapMut::from_bytes(strip, width as u32, plan.height as u32).ok_or(size)?;
                plan.draw(&mut canvas, layout);
                Ok(())
            })
            .collect::<Result<(), RenderError>>()?;
        let mut canvas = img.as_mut();
        let mut y = 0.0;
        for ((label, _), plan) in fonts.iter().zip(plans) {
            let room = width as f64 - 2.0 * MARGIN;
            super::labels::draw_line(
                &mut canvas,
                label,
                (MARGIN, y + 0.4 * LABEL_EM),
                LABEL_EM,
                room,
                Color::from_rgba8(0x44, 0x55, 0x99, 0xFF),
            );
            y += (label_h + plan.height) as f64;
        }
        Ok(img)
    }
}
