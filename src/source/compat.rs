//! Compatibility of a master with the default master: the same glyphs, and in each glyph
//! the same contours with the same number of points, the same sharp points, and the same
//! components in the same order, and the same anchor names in the same order (their
//! positions may differ). The glyph-level keys `unicode` and `mark` are the default
//! master's: a master's file may leave them out, and what it writes must be the default's.
//!
//! Problems are reported in the master's file, at the place to fix, and say what the
//! default master has. A glyph the master lacks is reported at the master's `folder` in
//! `font.toml`. Glyphs with errors of their own (in either master) are not compared.

use std::collections::HashMap;
use std::path::Path;

use super::designspace::MasterSpec;
use super::diagnostic::{Ctx, Diagnostics};
use super::emit;
use super::load::GlyphFile;

/// Compares every glyph of `master` (the files of `spec`'s folder) with `default`;
/// `font_toml` (path and text) is where a missing glyph is reported.
pub(super) fn check_master(
    spec: &MasterSpec,
    font_toml: (&Path, &str),
    default: &[GlyphFile],
    master: &[GlyphFile],
    out: &mut Diagnostics,
) {
    let in_master: HashMap<&str, &GlyphFile> =
        master.iter().map(|g| (g.glyph.name.as_str(), g)).collect();
    let mut ctx = Ctx::new(font_toml.0, font_toml.1, out);
    for d in default {
        // A sparse master draws the glyphs it has; the others blend from the rest.
        if !spec.sparse && !in_master.contains_key(d.glyph.name.as_str()) {
            let file = d.path.file_name().map(|f| f.to_string_lossy().into_owned());
            ctx.err(
                spec.folder_at,
                format!(
                    "master `{}` has no glyph `{}`; add {}/{} (a copy of {} with this \
                     master's coordinates)",
                    spec.name,
                    d.glyph.name,
                    spec.folder.trim_end_matches('/'),
                    file.as_deref().unwrap_or("?"),
                    d.path.display()
                ),
            );
        }
    }
    let in_default: HashMap<&str, &GlyphFile> =
        default.iter().map(|g| (g.glyph.name.as_str(), g)).collect();
    for m in master {
        let mut ctx = m.ctx(out);
        let Some(d) = in_default.get(m.glyph.name.as_str()) else {
            let at = if m.spans.name > 0 {
                m.spans.name
            } else {
                m.spans.start
            };
            ctx.err(
                at,
                format!(
                    "glyph `{}` is not in the default master; add it there too, or remove \
                     this file",
                    m.glyph.name
                ),
            );
            continue;
        };
        if d.complete && m.complete {
            check_glyph(&mut ctx, d, m);
        }
    }
}

/// One glyph of a master against the default's.
fn check_glyph(ctx: &mut Ctx<'_>, d: &GlyphFile, m: &GlyphFile) {
    let (dg, mg) = (&d.glyph, &m.glyph);
    if !mg.unicodes.is_empty() && mg.unicodes != dg.unicodes {
        ctx.err(
            m.spans.unicodes[0],
            format!(
                "`unicode` {} differs from the default master's {}; leave it out (a master \
                 has the default's code points) or make it the same",
                code_points(&mg.unicodes),
                code_points(&dg.unicodes),
            ),
        );
    }
    if mg.outline_mark && !dg.outline_mark {
        ctx.err(
            m.spans.mark,
            "`mark = \"outline\"` is not in the default master's file; write it there (the \
             default master's file says it for every master), or remove it here",
        );
    }

    let bases = |g: &crate::model::Glyph| -> Vec<String> {
        g.components.iter().map(|c| c.base.clone()).collect()
    };
    let (db, mb) = (bases(dg), bases(mg));
    if db != mb {
        let listed = if db.is_empty() {
            "none".to_string()
        } else {
            db.iter()
                .map(|b| format!("`{b}`"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let first = (0..db.len().min(mb.len())).find(|&i| db[i] != mb[i]);
        match first {
            Some(i) => ctx.err(
                m.spans.bases[i],
                format!(
                    "component {i} is `{}` here but `{}` in the default master, whose \
                     components are {listed}; masters need the same components in the same \
                     order",
                    mb[i], db[i]
                ),
            ),
            None if mb.len() > db.len() => ctx.err(
                m.spans.bases[db.len()],
                format!(
                    "component {} (`{}`) is not in the default master, whose components are \
                     {listed}; remove it",
                    db.len(),
                    mb[db.len()]
                ),
            ),
            None => ctx.err(
                m.spans.start,
                format!(
                    "this master has {} of the default master's {} components ({listed}); \
                     add `{}` after the others",
                    mb.len(),
                    db.len(),
                    db[mb.len()]
                ),
            ),
        }
    }

    let names = |g: &crate::model::Glyph| -> Vec<String> {
        g.anchors.iter().map(|a| a.name.clone()).collect()
    };
    let (da, ma) = (names(dg), names(mg));
    if da != ma {
        let listed = |names: &[String]| -> String {
            if names.is_empty() {
                "none".to_string()
            } else {
                let quoted: Vec<String> = names.iter().map(|n| format!("`{n}`")).collect();
                quoted.join(", ")
            }
        };
        let first = (0..da.len().max(ma.len())).find(|&i| da.get(i) != ma.get(i));
        let at = first
            .and_then(|i| m.spans.anchors.get(i).or(m.spans.anchors.last()))
            .copied()
            .unwrap_or(m.spans.start);
        ctx.err(
            at,
            format!(
                "anchors are {} here but {} in the default master; masters need the same \
                 anchor names in the same order (positions may differ)",
                listed(&ma),
                listed(&da)
            ),
        );
    }

    let (dc, mc) = (&dg.contours, &mg.contours);
    if mc.len() > dc.len() {
        ctx.err(
            m.spans.points[dc.len()][0],
            format!(
                "contour {} is not in the default master, which has {} {}; remove it (or add \
                 it to every master)",
                dc.len(),
                dc.len(),
                plural(dc.len(), "contour", "contours")
            ),
        );
    } else if mc.len() < dc.len() {
        let at = match m.spans.points.last() {
            Some(points) => points[0],
            None => m.spans.start,
        };
        ctx.err(
            at,
            format!(
                "this master has {} {}, the default master has {}; add contour {} ({} points \
                 in the default)",
                mc.len(),
                plural(mc.len(), "contour", "contours"),
                dc.len(),
                mc.len(),
                dc[mc.len()].points().len()
            ),
        );
    }
    for (c, (dcon, mcon)) in dc.iter().zip(mc).enumerate() {
        let (dp, mp) = (dcon.points(), mcon.points());
        let spans = &m.spans.points[c];
        if mp.len() != dp.len() {
            let (at, fix) = if mp.len() > dp.len() {
                (
                    spans[dp.len()],
                    format!(
                        "point {} and after are extra; remove {}",
                        dp.len(),
                        mp.len() - dp.len()
                    ),
                )
            } else {
                (
                    spans[mp.len() - 1],
                    format!(
                        "add {} after point {}",
                        plural(
                            dp.len() - mp.len(),
                            "1 point",
                            &format!("{} points", dp.len() - mp.len())
                        ),
                        mp.len() - 1
                    ),
                )
            };
            ctx.err(
                at,
                format!(
                    "contour {c} has {} points here, the default master has {}; {fix}",
                    mp.len(),
                    dp.len()
                ),
            );
            continue;
        }
        for (i, (a, b)) in dp.iter().zip(mp).enumerate() {
            if (a.s == 0.0) != (b.s == 0.0) {
                let (here, there) = (emit::number(b.s), emit::number(a.s));
                let msg = if b.s == 0.0 {
                    format!(
                        "point {i} of contour {c} is sharp (s = 0) here but s = {there} in the \
                         default master; a sharp point must be sharp in every master (a corner \
                         cannot appear mid-axis): make it s = 0 in every master, or non-zero \
                         here"
                    )
                } else {
                    format!(
                        "point {i} of contour {c} has s = {here} here but is sharp (s = 0) in \
                         the default master; a sharp point must be sharp in every master (a \
                         corner cannot appear mid-axis): make it s = 0 here"
                    )
                };
                ctx.err(spans[i], msg);
            }
        }
    }
}

fn plural<'a>(n: usize, one: &'a str, many: &'a str) -> &'a str {
    if n == 1 {
        one
    } else {
        many
    }
}

/// Code points as `font.toml` writes them: `0x0041`, or `[0x0041, 0x0061]`, or `none`.
fn code_points(cs: &[char]) -> String {
    match cs {
        [] => "none".to_string(),
        [c] => format!("0x{:04X}", u32::from(*c)),
        many => {
            let all: Vec<String> = many
                .iter()
                .map(|&c| format!("0x{:04X}", u32::from(c)))
                .collect();
            format!("[{}]", all.join(", "))
        }
    }
}
