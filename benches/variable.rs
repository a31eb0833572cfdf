//! The variable TTF backend (issue 16, item 4): `otf::variable_ttf` on the bundled typeface
//! with a second master against the static `otf::ttf` of the default master alone, in the
//! same run. Run: `cargo bench --bench variable`.
//!
//! The second master is the default with every point through one affine map (wider,
//! slanted), so it is compatible by construction, as in `tests/it/variable.rs`.

use std::hint::black_box;
use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion};
use kurbo::Affine;
use xglyph::designspace::{Axis, Designspace, Location};
use xglyph::family::{MasterGlyph, OutlinedFamily, OutlinedMaster};

fn family() -> OutlinedFamily {
    let font = xglyph::pipeline::load(Path::new("glyphs"), None)
        .expect("glyphs/ loads")
        .font;
    let designspace = Designspace {
        axes: vec![Axis::linear("wght", "Weight", 400.0, 400.0, 700.0)],
        instances: vec![],
        rules: Vec::new(),
        rules_last: false,
    };
    let bold = Location([("wght".to_string(), 700.0)].into_iter().collect());
    let model = designspace
        .model(std::slice::from_ref(&bold))
        .expect("valid");
    let map = Affine::new([1.15, 0.0, 0.05, 0.98, 0.0, 4.0]);
    let glyphs = font
        .glyphs
        .iter()
        .map(|g| MasterGlyph {
            advance: g.advance * 1.15,
            path: map * g.path.clone(),
            drawn: true,
        })
        .collect();
    OutlinedFamily {
        designspace,
        masters: vec![OutlinedMaster {
            name: "Bold".into(),
            location: bold,
            glyphs,
            kerning: font.kerning.clone(),
        }],
        models: xglyph::model::GlyphModels::full(1, &model, font.glyphs.len()),
        default: font,
        model,
    }
}

fn bench(c: &mut Criterion) {
    let family = family();
    let mut group = c.benchmark_group("variable");
    group.bench_function("static ttf (default master)", |b| {
        b.iter(|| xglyph::otf::ttf(black_box(&family.default)).expect("builds"))
    });
    group.bench_function("variable ttf (2 masters)", |b| {
        b.iter(|| xglyph::otf::variable_ttf(black_box(&family)).expect("builds"))
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
