//! Test fonts made in code.

use std::path::Path;

use kurbo::BezPath;
use skrifa::instance::{LocationRef, Size};
use skrifa::outline::{DrawSettings, OutlinePen};
use skrifa::raw::TableProvider;
use skrifa::{FontRef, GlyphId, MetadataProvider};

use ttf_parser::Face;
use xglyph::import::font::glyph_outline;
use xglyph::model::{Contour, Font, FontInfo, Glyph};
use xglyph::otf::{otf, ttf, PULLED};
use xglyph::outline::{outline_font, OutlinedFont};

use super::temp::TempFolder;
use xglyph::source::load_font;
use xglyph::xspline::ControlPoint;

/// The `font.toml` of the small fonts the tests write: 1000 units per em.
pub const SMALL_FONT: &str = "family = \"T\"\nunits_per_em = 1000\nascender = 800\n\
                              descender = -200\nx_height = 500\ncap_height = 700\n";

/// A fresh folder `xglyph-<tag>-…` in the temp dir holding [`SMALL_FONT`] as
/// `font.toml` and `files` (name, text); removed when dropped.
pub fn small_font_folder<S: AsRef<str>>(tag: &str, files: &[(&str, S)]) -> TempFolder {
    let dir = TempFolder::new(tag);
    std::fs::write(dir.join("font.toml"), SMALL_FONT).expect("write font.toml");
    for (name, text) in files {
        std::fs::write(dir.join(name), text.as_ref()).expect("write");
    }
    dir
}

/// The mini test font with its glyphs replaced by `n` squares mapped from U+4E00 on, and no
/// kerning: a font without Latin, so no sheet label is in its own glyphs.
pub fn square_ideographs(n: u32) -> Font {
    let mut font = load_font(&Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mini"))
        .expect("mini loads")
        .0;
    let square = Contour::new(
        [(100.0, 0.0), (800.0, 0.0), (800.0, 700.0), (100.0, 700.0)]
            .iter()
            .map(|&(x, y)| ControlPoint::new(x, y, 0.0))
            .collect(),
    )
    .expect("a square is a valid contour");
    font.glyphs = (0..n)
        .map(|i| {
            let c = char::from_u32(0x4E00 + i).expect("U+4E00 + n is a character");
            Glyph {
                name: format!("uni{:04X}", u32::from(c)),
                unicodes: vec![c],
                advance: 1000.0,
                contours: vec![square.clone()],
                components: vec![],
                anchors: Vec::new(),
                outline_mark: false,
            }
        })
        .collect();
    font.kerning.clear();
    font
}

/// The id of the glyph `post` names `name` (panics when there is none).
pub fn glyph_id(font: &FontRef, name: &str) -> GlyphId {
    let post = font.post().expect("post");
    (0..font.maxp().expect("maxp").num_glyphs())
        .map(|g| GlyphId::new(u32::from(g)))
        .find(|&g| post.glyph_name(g.try_into().expect("16-bit")) == Some(name))
        .unwrap_or_else(|| panic!("no glyph {name}"))
}

/// A glyph's outline read back with skrifa at `location` (unhinted, font units).
pub fn skrifa_outline(font: &FontRef, gid: GlyphId, location: LocationRef) -> BezPath {
    let mut pen = Pen(BezPath::new());
    font.outline_glyphs()
        .get(gid)
        .expect("the glyph is in the font")
        .draw(DrawSettings::unhinted(Size::unscaled(), location), &mut pen)
        .expect("skrifa draws the glyph");
    pen.0
}

/// A skrifa pen into a kurbo path.
struct Pen(BezPath);

impl OutlinePen for Pen {
    fn move_to(&mut self, x: f32, y: f32) {
        self.0.move_to((f64::from(x), f64::from(y)));
    }
    fn line_to(&mut self, x: f32, y: f32) {
        self.0.line_to((f64::from(x), f64::from(y)));
    }
    fn quad_to(&mut self, cx0: f32, cy0: f32, x: f32, y: f32) {
        self.0.quad_to(
            (f64::from(cx0), f64::from(cy0)),
            (f64::from(x), f64::from(y)),
        );
    }
    fn curve_to(&mut self, cx0: f32, cy0: f32, cx1: f32, cy1: f32, x: f32, y: f32) {
        self.0.curve_to(
            (f64::from(cx0), f64::from(cy0)),
            (f64::from(cx1), f64::from(cy1)),
            (f64::from(x), f64::from(y)),
        );
    }
    fn close(&mut self) {
        self.0.close_path();
    }
}

/// `glyphs` as a font of `em` units per em (tolerance 1/1000 em), outlined, and each
/// glyph read back from its TTF and its OTF (`("TTF", path)`, `("OTF", path)`), in the
/// outlined font's order. Asserts the grid's bound on every read-back outline: within
/// `PULLED` of the exact one, plus the tolerance for the TTF's quadratics.
pub fn read_back_from_the_grid(
    family: &str,
    em: u16,
    glyphs: Vec<Glyph>,
) -> (Font, OutlinedFont, Vec<[(&'static str, BezPath); 2]>) {
    let font = Font {
        info: FontInfo::with_em(family, em),
        glyphs,
        kerning: Vec::new(),
        features: None,
    };
    let outlines = outline_font(&font, font.info.tolerance);
    let (ttf_bytes, otf_bytes) = (ttf(&outlines).unwrap(), otf(&outlines).unwrap());
    let faces = [
        (
            "TTF",
            Face::parse(&ttf_bytes, 0).unwrap(),
            font.info.tolerance + PULLED,
        ),
        ("OTF", Face::parse(&otf_bytes, 0).unwrap(), PULLED),
    ];
    let read = outlines
        .glyphs
        .iter()
        .map(|glyph| {
            faces.each_ref().map(|(what, face, bound)| {
                let gid = face.glyph_index_by_name(&glyph.name).expect("the glyph");
                let path = glyph_outline(face, gid).unwrap_or_default();
                let d = super::paths::two_sided(&path, &glyph.path, 48);
                assert!(d <= *bound, "{what} {} {d}", glyph.name);
                (*what, path)
            })
        })
        .collect();
    (font, outlines, read)
}
