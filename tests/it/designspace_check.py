"""Compares variable fonts compiled from an exported designspace with xglyph's own variable
TTF (tests/it/designspace.rs).

Usage: designspace_check.py DESIGNSPACE XGLYPH_VF FONTMAKE_VF FONTC_VF TOLERANCE POS...

Each POS is a user location: `wght=650,wdth=87.5`, or a bare number for `wght`.

Prints what fontTools.designspaceLib reads (`axes: …`, `sources: …`, `instances: …`, for
the Rust test to compare with the sources), then checks, printing each measured figure:
- every source UFO opens with ufoLib2 and has the same glyphs, in the same order, with the
  same number of points per contour as the default master (the UFOs interpolate); a source
  on a layer or a UFO with fewer glyphs (a sparse master) has some of the default's glyphs,
  each with its structure;
- each compiled font has xglyph's fvar axes (tag, min, default, max), avar segment maps
  (within one F2Dot14 step), named instances (subfamily name and coordinates), glyph set
  and cmap;
- advances at each master (fontTools.varLib.instancer) equal xglyph's there and the master
  UFO's widths;
- kerning at each master equals xglyph's there;
- outlines at every POS: each glyph of the compiled font's instance is
  within a stated distance of xglyph's instance (dense two-sided distance of flattened
  pens, helpers of ufo_check.py). The bound: xglyph's TTF converts the cubics to
  quadratics within TOLERANCE, fontmake (cu2qu) and fontc within 1/1000 em; both round to
  the integer grid at the masters and in the instancer (at most sqrt(2)/2 units per point
  each); plus the flattening slack.
Prints "designspace_check: all passed" when every check holds; exits 1 otherwise.
"""

import math
import os
import sys

import ufoLib2
from fontTools.designspaceLib import DesignSpaceDocument
from fontTools.ttLib import TTFont
from fontTools.varLib import instancer

from ufo_check import FLAT_SLACK, distance, flat, kerning


def fvar_axes(font):
    return [(a.axisTag, a.minValue, a.defaultValue, a.maxValue) for a in font["fvar"].axes]


def fvar_instances(font):
    name = font["name"]
    tags = [a.axisTag for a in font["fvar"].axes]
    return [
        (str(name.getDebugName(i.subfamilyNameID)), tuple(i.coordinates[t] for t in tags))
        for i in font["fvar"].instances
    ]


def avar(font):
    """Each axis's segment map, as {from: to}; the identity when the font has no avar."""
    tags = [a.axisTag for a in font["fvar"].axes]
    if "avar" not in font:
        return {t: {-1.0: -1.0, 0.0: 0.0, 1.0: 1.0} for t in tags}
    return {t: dict(font["avar"].segments[t]) for t in tags}


def same_avar(a, b):
    """The same segment maps, each coordinate within one F2Dot14 step (compilers round
    the normalised values their own way)."""
    step = 1.0 / 16384
    ma, mb = avar(a), avar(b)
    if ma.keys() != mb.keys():
        return False
    for tag in ma:
        pa, pb = sorted(ma[tag].items()), sorted(mb[tag].items())
        if len(pa) != len(pb):
            return False
        for (fa, ta), (fb, tb) in zip(pa, pb):
            if abs(fa - fb) > step or abs(ta - tb) > step:
                return False
    return True


def at(path, location):
    return instancer.instantiateVariableFont(TTFont(path), dict(location), inplace=False)


def position(arg):
    """A POS argument as a sorted tuple of (tag, user value)."""
    if "=" not in arg:
        return (("wght", float(arg)),)
    pairs = (p.split("=") for p in arg.split(","))
    return tuple(sorted((tag, float(v)) for tag, v in pairs))


def describe(location):
    return ", ".join(f"{tag} {v:g}" for tag, v in location)


def main():
    ds_path, ours_path, fontmake_path, fontc_path, tolerance = sys.argv[1:6]
    positions = [position(p) for p in sys.argv[6:]]
    tolerance = float(tolerance)
    failures = []

    def check(ok, what):
        print(("ok    " if ok else "FAIL  ") + what)
        if not ok:
            failures.append(what)

    doc = DesignSpaceDocument.fromfile(ds_path)
    fmt = lambda v: f"{v:g}"
    print("axes: " + ", ".join(f"{a.tag} {a.name} {fmt(a.minimum)} {fmt(a.default)} {fmt(a.maximum)}" for a in doc.axes))
    print("sources: " + ", ".join(
        f"{s.filename} {s.styleName} " + " ".join(f"{k}={fmt(v)}" for k, v in sorted(s.location.items()))
        for s in doc.sources
    ))
    print("instances: " + ", ".join(
        f"{i.styleName} " + " ".join(f"{k}={fmt(v)}" for k, v in sorted(i.location.items()))
        for i in doc.instances
    ))

    base = os.path.dirname(ds_path)
    fonts = [ufoLib2.Font.open(os.path.join(base, s.filename), validate=True) for s in doc.sources]
    # Each source's glyphs: its layer's when it names one.
    ufos = [f.layers[s.layerName] if s.layerName else f for s, f in zip(doc.sources, fonts)]
    default = fonts[0]
    order = default.lib["public.glyphOrder"]
    structure = lambda ufo: {
        g.name: [len(c.points) for c in g.contours] + [c.baseGlyph for c in g.components] for g in ufo
    }
    want = structure(default)
    for s, font, ufo in zip(doc.sources, fonts, ufos):
        mine = structure(ufo)
        # A sparse source: a layer, or a UFO that lacks some of the default's glyphs.
        if s.layerName or set(mine) < set(want):
            where = f"{s.filename} layer {s.layerName}" if s.layerName else s.filename
            check(len(mine) > 0 and all(want.get(g) == v for g, v in mine.items()),
                  f"{where}: {len(mine)} glyphs ({', '.join(sorted(mine))}), "
                  "each with the default master's contours and points")
            continue
        check(font.lib["public.glyphOrder"] == order and structure(ufo) == want,
              f"{s.filename}: {len(ufo)} glyphs, same contours and points as the default master")

    ours = TTFont(ours_path)
    # Source locations are design values; the instancer takes user values, by tag.
    tags = {a.name: a.tag for a in doc.axes}
    masters = {
        tuple(sorted((tags[k], v) for k, v in doc.map_backward(s.location).items())): ufo
        for s, ufo in zip(doc.sources, ufos)
    }
    ours_at = {w: at(ours_path, w) for w in sorted(set(positions) | set(masters))}
    rounding = math.sqrt(2) / 2
    upm = default.info.unitsPerEm
    bound = tolerance + upm / 1000 + 4 * rounding + FLAT_SLACK
    for path in (ours_path, fontmake_path, fontc_path):
        label = path.rsplit("/", 1)[-1]
        font = TTFont(path)
        check(fvar_axes(font) == fvar_axes(ours), f"{label}: fvar axes {fvar_axes(font)}")
        check(same_avar(font, ours), f"{label}: avar {avar(font)}")
        check(fvar_instances(font) == fvar_instances(ours), f"{label}: named instances {fvar_instances(font)}")
        check(sorted(font.getGlyphOrder()) == sorted(ours.getGlyphOrder()), f"{label}: glyph set ({len(font.getGlyphOrder())} glyphs)")
        check(font.getBestCmap() == ours.getBestCmap(), f"{label}: cmap ({len(font.getBestCmap())} code points)")
        for w, ufo in sorted(masters.items()):
            inst = at(path, w)
            widths = {g.name: round(g.width) for g in ufo}
            mine = ours_at[w]
            check(
                all(inst["hmtx"][g][0] == mine["hmtx"][g][0] == widths.get(g, mine["hmtx"][g][0]) for g in order),
                f"{label}: advances at {describe(w)} (xglyph's and the UFO's)",
            )
            k, ok = kerning(inst), kerning(mine)
            check(k == ok, f"{label}: kerning at {describe(w)} ({len(k)} pairs)")
        if path == ours_path:
            continue
        for w in positions:
            gs, mine = at(path, w).getGlyphSet(), ours_at[w].getGlyphSet()
            worst, worst_glyph = 0.0, None
            for name in order:
                d = distance(flat(gs, name), flat(mine, name))
                if d > worst:
                    worst, worst_glyph = d, name
            check(worst <= bound, f"{label}: outlines at {describe(w)} within {bound:.3f} of xglyph's (worst {worst:.3f} in {worst_glyph})")
    if failures:
        print(f"designspace_check: {len(failures)} failed")
        sys.exit(1)
    print("designspace_check: all passed")


if __name__ == "__main__":
    main()
