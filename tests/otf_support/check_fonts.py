#!/usr/bin/env python3
"""fontTools checks of the fonts built by `examples/otf_fixture.rs` (run by .ci/check-fonts).

Usage: check_fonts.py OUT_DIR

OUT_DIR holds expected.json (from the model), the fonts it names, and for each font
FONT.sanitized (the OpenType Sanitizer's output). Every font must load in fontTools with
the expected glyph order, cmap, advances, metrics, names and GPOS kerning; every glyph must
draw (which runs fontTools' glyf / Type 2 charstring interpreters) inside the head box; and
OTS must have kept every table. Prints one line per problem and exits 1 if there is any.
"""

import json
import os
import sys

from fontTools.pens.boundsPen import BoundsPen
from fontTools.ttLib import TTFont


def gpos_pairs(font):
    """{(left, right): x_advance} from every PairPos format 1 subtable in GPOS."""
    pairs = {}
    if "GPOS" not in font:
        return pairs
    for lookup in font["GPOS"].table.LookupList.Lookup:
        for sub in lookup.SubTable:
            if getattr(sub, "Format", None) != 1 or not hasattr(sub, "PairSet"):
                continue
            for first, pair_set in zip(sub.Coverage.glyphs, sub.PairSet):
                for rec in pair_set.PairValueRecord:
                    value = getattr(rec.Value1, "XAdvance", 0) if rec.Value1 else 0
                    pairs[(first, rec.SecondGlyph)] = value
    return pairs


def check(path, expected, problems):
    name = os.path.basename(path)

    def fail(message):
        problems.append(f"{name}: {message}")

    font = TTFont(path)
    order = font.getGlyphOrder()
    if order != expected["glyph_order"]:
        fail(f"glyph order {order} != expected {expected['glyph_order']}")

    cmap = {str(k): v for k, v in font.getBestCmap().items()}
    if cmap != expected["cmap"]:
        fail(f"cmap {cmap} != expected {expected['cmap']}")

    advances = {g: font["hmtx"][g][0] for g in order}
    if advances != expected["advances"]:
        fail(f"advances {advances} != expected {expected['advances']}")

    head, hhea, os2 = font["head"], font["hhea"], font["OS/2"]
    # One line box everywhere: the model's ascender/descender widened to the ink box.
    ascender = max(expected["ascender"], head.yMax)
    descender = min(expected["descender"], head.yMin)
    metrics = {
        "head.unitsPerEm": (head.unitsPerEm, expected["units_per_em"]),
        "hhea.ascent": (hhea.ascent, ascender),
        "hhea.descent": (hhea.descent, descender),
        "hhea.lineGap": (hhea.lineGap, 0),
        "OS/2.sTypoAscender": (os2.sTypoAscender, ascender),
        "OS/2.sTypoDescender": (os2.sTypoDescender, descender),
        "OS/2.usWinAscent": (os2.usWinAscent, max(ascender, 0)),
        "OS/2.usWinDescent": (os2.usWinDescent, max(-descender, 0)),
        "OS/2.sTypoLineGap": (os2.sTypoLineGap, 0),
        "OS/2.sxHeight": (os2.sxHeight, expected["x_height"]),
        "OS/2.sCapHeight": (os2.sCapHeight, expected["cap_height"]),
        "OS/2.fsSelection USE_TYPO_METRICS": (bool(os2.fsSelection & 0x80), True),
        "OS/2.usWinAscent covers yMax": (os2.usWinAscent >= head.yMax, True),
        "OS/2.usWinDescent covers yMin": (os2.usWinDescent >= -head.yMin, True),
    }
    for what, (got, want) in metrics.items():
        if got != want:
            fail(f"{what} is {got}, expected {want}")

    # Typographic family/style (IDs 16/17) when present, else the legacy IDs 1/2.
    names = font["name"]
    for ids, want in (((16, 1), expected["family"]), ((17, 2), expected["style"])):
        got = next((n for n in map(names.getDebugName, ids) if n is not None), None)
        if got != want:
            fail(f"name ID {ids[0]}/{ids[1]} is {got!r}, expected {want!r}")

    pairs = gpos_pairs(font)
    want_pairs = {(l, r): v for l, r, v in expected["kerning"]}
    if pairs != want_pairs:
        fail(f"GPOS kerning {pairs} != expected {want_pairs}")
    if want_pairs:
        features = [r.FeatureTag for r in font["GPOS"].table.FeatureList.FeatureRecord]
        # kern first; mark and mkmk from the anchors (tests/it/features.rs checks them).
        if features[:1] != ["kern"] or not set(features) <= {"kern", "mark", "mkmk"}:
            fail(f"GPOS features {features}, expected kern (then mark, mkmk)")

    if "CFF " in font:
        # Type 2 widths must agree with hmtx (nominalWidthX + first operand, or default).
        top = font["CFF "].cff.topDictIndex[0]
        for g in order:
            charstring = top.CharStrings[g]
            charstring.decompile()
            charstring.draw(BoundsPen(None))
            private = charstring.private
            width = getattr(charstring, "width", private.defaultWidthX)
            if width != advances[g]:
                fail(f"CFF width of {g} is {width}, hmtx advance {advances[g]}")

    glyph_set = font.getGlyphSet()
    for g in order:
        pen = BoundsPen(glyph_set)
        glyph_set[g].draw(pen)
        if pen.bounds is None:
            continue
        x0, y0, x1, y1 = pen.bounds
        if x0 < head.xMin or y0 < head.yMin or x1 > head.xMax or y1 > head.yMax:
            fail(f"glyph {g} bounds {pen.bounds} outside head box")

    kept = TTFont(path + ".sanitized")
    dropped = sorted(set(font.keys()) - set(kept.keys()))
    if dropped:
        fail(f"OTS dropped tables {dropped}")


def main():
    out_dir = sys.argv[1]
    with open(os.path.join(out_dir, "expected.json"), encoding="utf-8") as f:
        expected = json.load(f)
    problems = []
    for font_file in expected["fonts"]:
        path = os.path.join(out_dir, font_file)
        try:
            check(path, expected, problems)
        except Exception as e:  # a font fontTools cannot read is a finding, not a crash
            problems.append(f"{font_file}: fontTools failed: {type(e).__name__}: {e}")
    for p in problems:
        print(f"check-fonts: fontTools: {p}")
    if problems:
        return 1
    print(f"check-fonts: fontTools: {', '.join(expected['fonts'])}: glyph order, cmap, "
          f"advances, metrics, names, kerning OK")
    return 0


if __name__ == "__main__":
    sys.exit(main())
