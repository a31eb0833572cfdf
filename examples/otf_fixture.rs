//! Builds the TTF, OTF and specimen pages of a font directory, plus the expectations the
//! external checks (`.ci/check-fonts`) compare them with.
//!
//! Usage: `cargo run --example otf_fixture -- FONT_DIR OUT_DIR`
//!
//! Writes `<Family>-<Style>.ttf|otf`, `<Family>-<Style>.ttf.html|otf.html` (specimens) and
//! `expected.json`: glyph order (PostScript names), cmap, advances, kerning (by PostScript
//! name), vertical metrics and each specimen's expected measured width. The expectations
//! come from the model, not from the built fonts.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use serde_json::{json, Map, Value};
use xglyph::otf::{glyph_order, otf, specimen_html, ttf};
use xglyph::outline::outline_font;
use xglyph::source::load_font;
use xglyph::write::write_all_atomic;

fn run(font_dir: &Path, out_dir: &Path) -> Result<Vec<String>, String> {
    let (font, _warnings) = load_font(font_dir).map_err(|diags| {
        let lines: Vec<String> = diags.iter().map(ToString::to_string).collect();
        format!("{} has errors:\n{}", font_dir.display(), lines.join("\n"))
    })?;
    let font = outline_font(&font, font.info.tolerance);
    let stem: String = format!("{}-{}", font.info.family, font.info.style)
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect();
    let ttf_name = format!("{stem}.ttf");
    let otf_name = format!("{stem}.otf");
    let ttf_bytes = ttf(&font).map_err(|e| format!("TTF: {e}"))?;
    let otf_bytes = otf(&font).map_err(|e| format!("OTF: {e}"))?;
    let order = glyph_order(&font).map_err(|e| e.to_string())?;

    let ps_name = |model: &str| {
        order
            .iter()
            .find(|g| g.model_name == model)
            .map(|g| g.ps_name.clone())
    };
    let mut cmap = Map::new();
    let mut advances = Map::new();
    for g in &order {
        for &c in &g.unicodes {
            cmap.insert(u32::from(c).to_string(), Value::from(g.ps_name.clone()));
        }
        advances.insert(g.ps_name.clone(), Value::from(g.advance));
    }
    let kerning: Vec<Value> = font
        .kerning
        .iter()
        .filter_map(|k| {
            let value = k.value.round() as i64;
            let (left, right) = (ps_name(&k.left)?, ps_name(&k.right)?);
            (value != 0).then(|| json!([left, right, value]))
        })
        .collect();
    let expected = json!({
        "family": font.info.family,
        "style": font.info.style,
        "units_per_em": font.info.units_per_em,
        "ascender": font.info.ascender.round() as i64,
        "descender": font.info.descender.round() as i64,
        "x_height": font.info.x_height.round() as i64,
        "cap_height": font.info.cap_height.round() as i64,
        "glyph_order": order.iter().map(|g| g.ps_name.clone()).collect::<Vec<_>>(),
        "cmap": cmap,
        "advances": advances,
        "kerning": kerning,
        "fonts": [ttf_name, otf_name],
    });
    let files: Vec<(PathBuf, Vec<u8>)> = vec![
        (out_dir.join(&ttf_name), ttf_bytes),
        (out_dir.join(&otf_name), otf_bytes),
        (
            out_dir.join(format!("{ttf_name}.html")),
            specimen_html(&font, &ttf_name).into_bytes(),
        ),
        (
            out_dir.join(format!("{otf_name}.html")),
            specimen_html(&font, &otf_name).into_bytes(),
        ),
        (
            out_dir.join("expected.json"),
            serde_json::to_vec_pretty(&expected).map_err(|e| e.to_string())?,
        ),
    ];
    std::fs::create_dir_all(out_dir).map_err(|e| format!("{}: {e}", out_dir.display()))?;
    write_all_atomic(&files).map_err(|e| format!("{}: {e}", out_dir.display()))?;
    Ok(files.iter().map(|(p, _)| p.display().to_string()).collect())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [font_dir, out_dir] = args.as_slice() else {
        eprintln!("usage: otf_fixture FONT_DIR OUT_DIR");
        return ExitCode::from(2);
    };
    match run(Path::new(font_dir), Path::new(out_dir)) {
        Ok(files) => {
            for f in files {
                println!("{f}");
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("otf_fixture: {e}");
            ExitCode::FAILURE
        }
    }
}
