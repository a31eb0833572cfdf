"""Compares fonts compiled from an exported UFO with xglyph's own TTF (tests/it/ufo.rs).

Usage: ufo_check.py UFO XGLYPH_TTF FONTMAKE_TTF FONTC_TTF TOLERANCE

Checks, printing each measured figure:
- ufoLib2 opens the UFO (and fontTools' UFOReader validates it);
- each compiled font has xglyph's glyph set, cmap, advances and kerning (GPOS pair values,
  class and glyph pairs, read with fontTools);
- outlines: every glyph of each TTF, components resolved with fontTools pens, is within a
  stated distance of the UFO's cubic outline (dense two-sided distance of flattened pens,
  not point equality). The bounds: xglyph's TTF converts to quadratics within TOLERANCE;
  fontmake (cu2qu) and fontc within 1/1000 em by default; every TTF rounds to the integer
  grid (at most sqrt(2)/2 units per point); plus 0.05 units of flattening error.
Prints "ufo_check: all passed" when every check holds; exits 1 otherwise.
"""

import math
import sys

import ufoLib2
from fontTools.pens.basePen import BasePen
from fontTools.ttLib import TTFont
from fontTools.ufoLib import UFOReader

FLAT_STEPS = 24
FLAT_SLACK = 0.05


class FlatPen(BasePen):
    """Flattens any outline into closed polylines."""

    def __init__(self, glyph_set):
        super().__init__(glyph_set)
        self.polys = []
        self.cur = None

    def _moveTo(self, p):
        self.cur = [p]
        self.polys.append(self.cur)

    def _lineTo(self, p):
        self.cur.append(p)

    def _curveToOne(self, p1, p2, p3):
        p0 = self.cur[-1]
        for i in range(1, FLAT_STEPS + 1):
            t = i / FLAT_STEPS
            u = 1 - t
            self.cur.append(
                tuple(
                    u * u * u * a + 3 * u * u * t * b + 3 * u * t * t * c + t * t * t * d
                    for a, b, c, d in zip(p0, p1, p2, p3)
                )
            )

    def _qCurveToOne(self, p1, p2):
        p0 = self.cur[-1]
        for i in range(1, FLAT_STEPS + 1):
            t = i / FLAT_STEPS
            u = 1 - t
            self.cur.append(
                tuple(u * u * a + 2 * u * t * b + t * t * c for a, b, c in zip(p0, p1, p2))
            )

    def _closePath(self):
        if self.cur and self.cur[0] != self.cur[-1]:
            self.cur.append(self.cur[0])

    _endPath = _closePath


def segments(polys):
    return [(p[i], p[i + 1]) for p in polys for i in range(len(p) - 1)]


def seg_dist(p, a, b):
    ax, ay = a
    dx, dy = b[0] - ax, b[1] - ay
    L = dx * dx + dy * dy
    t = 0.0 if L == 0 else max(0.0, min(1.0, ((p[0] - ax) * dx + (p[1] - ay) * dy) / L))
    return math.hypot(p[0] - ax - t * dx, p[1] - ay - t * dy)


class Grid:
    """Segments bucketed by cell for nearest-segment queries."""

    def __init__(self, segs, cell=20.0):
        self.cell = cell
        self.cells = {}
        for s in segs:
            (x0, y0), (x1, y1) = s
            for cx in range(int(math.floor(min(x0, x1) / cell)), int(math.floor(max(x0, x1) / cell)) + 1):
                for cy in range(int(math.floor(min(y0, y1) / cell)), int(math.floor(max(y0, y1) / cell)) + 1):
                    self.cells.setdefault((cx, cy), []).append(s)

    def nearest(self, p):
        cx, cy = int(math.floor(p[0] / self.cell)), int(math.floor(p[1] / self.cell))
        best = math.inf
        r = 0
        while r < 200:
            for i in range(cx - r, cx + r + 1):
                for j in range(cy - r, cy + r + 1):
                    if max(abs(i - cx), abs(j - cy)) != r:
                        continue
                    for a, b in self.cells.get((i, j), ()):
                        best = min(best, seg_dist(p, a, b))
            # Anything in a further ring is at least r * cell away.
            if best <= r * self.cell:
                return best
            r += 1
        return best


def one_sided(pa, pb):
    pts = [p for poly in pa for p in poly]
    segs = segments(pb)
    if not pts and not segs:
        return 0.0
    if not pts or not segs:
        return math.inf
    grid = Grid(segs)
    return max(grid.nearest(p) for p in pts)


def distance(pa, pb):
    return max(one_sided(pa, pb), one_sided(pb, pa))


def flat(glyph_set, name):
    pen = FlatPen(glyph_set)
    glyph_set[name].draw(pen)
    return pen.polys


def kerning(font):
    """(left, right) -> x advance adjustment, every nonzero pair of GPOS pair lookups."""
    pairs = {}
    if "GPOS" not in font:
        return pairs
    order = font.getGlyphOrder()
    for lookup in font["GPOS"].table.LookupList.Lookup:
        for st in lookup.SubTable:
            if lookup.LookupType == 9:
                st = st.ExtSubTable
            if st.LookupType != 2:
                continue
            cov = st.Coverage.glyphs
            if st.Format == 1:
                for left, ps in zip(cov, st.PairSet):
                    for rec in ps.PairValueRecord:
                        v = getattr(rec.Value1, "XAdvance", 0) if rec.Value1 else 0
                        pairs.setdefault((left, rec.SecondGlyph), v)
            else:
                c1 = st.ClassDef1.classDefs
                c2 = st.ClassDef2.classDefs
                for left in cov:
                    row = st.Class1Record[c1.get(left, 0)]
                    for right in order:
                        rec = row.Class2Record[c2.get(right, 0)]
                        v = getattr(rec.Value1, "XAdvance", 0) if rec.Value1 else 0
                        if v:
                            pairs.setdefault((left, right), v)
    return {k: v for k, v in pairs.items() if v}


def main():
    ufo_path, ours_path, fontmake_path, fontc_path, tolerance = sys.argv[1:6]
    tolerance = float(tolerance)
    failures = []

    def check(ok, what):
        print(("ok    " if ok else "FAIL  ") + what)
        if not ok:
            failures.append(what)

    ufo = ufoLib2.Font.open(ufo_path, validate=True)
    reader = UFOReader(ufo_path, validate=True)
    check(len(ufo) == len(reader.getGlyphSet().keys()), f"ufoLib2 opens the UFO: {len(ufo)} glyphs")
    upm = ufo.info.unitsPerEm
    ours = TTFont(ours_path)
    rounding = math.sqrt(2) / 2
    bounds = {
        ours_path: tolerance + rounding + FLAT_SLACK,
        fontmake_path: upm / 1000 + rounding + FLAT_SLACK,
        fontc_path: upm / 1000 + rounding + FLAT_SLACK,
    }
    ufo_outlines = {name: flat(ufo, name) for name in ufo.keys()}
    our_kerning = kerning(ours)
    plist_kerning = {k: v for k, v in ufo.kerning.items() if v}
    check(our_kerning == plist_kerning, f"xglyph TTF: {len(our_kerning)} kerning pairs, as kerning.plist")
    for path in (ours_path, fontmake_path, fontc_path):
        label = path.rsplit("/", 1)[-1]
        font = TTFont(path)
        gs = font.getGlyphSet()
        check(sorted(font.getGlyphOrder()) == sorted(ours.getGlyphOrder()), f"{label}: glyph set ({len(font.getGlyphOrder())} glyphs)")
        check(font.getBestCmap() == ours.getBestCmap(), f"{label}: cmap ({len(font.getBestCmap())} code points)")
        check(
            all(font["hmtx"][g][0] == ours["hmtx"][g][0] for g in ours.getGlyphOrder()),
            f"{label}: advances",
        )
        k = kerning(font)
        diff = {p for p in set(k) | set(our_kerning) if k.get(p) != our_kerning.get(p)}
        check(not diff, f"{label}: kerning ({len(k)} pairs; differing: {sorted(diff)[:5]})")
        worst, worst_glyph = 0.0, None
        for name in ufo.keys():
            d = distance(flat(gs, name), ufo_outlines[name])
            if d > worst:
                worst, worst_glyph = d, name
        check(worst <= bounds[path], f"{label}: outlines within {bounds[path]:.3f} of the UFO's (worst {worst:.3f} in {worst_glyph})")
    if failures:
        print(f"ufo_check: {len(failures)} failed")
        sys.exit(1)
    print("ufo_check: all passed")


if __name__ == "__main__":
    main()
