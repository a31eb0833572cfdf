"""Compares two variable fonts glyph by glyph (tests/it/sparse_import.rs, discrete_import.rs).

Usage: vf_compare.py OURS THEIRS PLACES GLYPH...

PLACES is `;`-separated, each place `tag=value,…` in user values (an axis a font has and
the place leaves out is at its default). Each font is instanced there with fontTools'
instancer. Prints JSON: per place (as written) and glyph, the two-sided distance between
the outlines (dense samples of each to the other's polyline), each one's contour count,
advance and bounding-box width.
"""

import json
import sys

import numpy as np
from fontTools.pens.basePen import BasePen
from fontTools.pens.boundsPen import BoundsPen
from fontTools.ttLib import TTFont
from fontTools.varLib.instancer import instantiateVariableFont


def samples(font, name, steps=16):
    gs = font.getGlyphSet()
    contours = []

    class P(BasePen):
        def _moveTo(self, p):
            self.cur = self.start = p
            contours.append([p])

        def _lineTo(self, p):
            a = self.cur
            for i in range(1, steps + 1):
                t = i / steps
                contours[-1].append((a[0] + (p[0] - a[0]) * t, a[1] + (p[1] - a[1]) * t))
            self.cur = p

        def _qCurveToOne(self, c, p):
            a = self.cur
            for i in range(1, steps + 1):
                t = i / steps
                u = 1 - t
                contours[-1].append(tuple(u * u * a[k] + 2 * u * t * c[k] + t * t * p[k] for k in range(2)))
            self.cur = p

        def _curveToOne(self, c1, c2, p):
            a = self.cur
            for i in range(1, steps + 1):
                t = i / steps
                u = 1 - t
                contours[-1].append(
                    tuple(u**3 * a[k] + 3 * u * u * t * c1[k] + 3 * u * t * t * c2[k] + t**3 * p[k] for k in range(2))
                )
            self.cur = p

        def _closePath(self):
            if self.cur != self.start:
                self._lineTo(self.start)

    gs[name].draw(P(gs))
    bounds = BoundsPen(gs)
    gs[name].draw(bounds)
    return contours, gs[name].width, bounds.bounds


def one_sided(xs, ys):
    """The largest distance from a sample of `xs` to the polylines of `ys`."""
    X = np.array([p for c in xs for p in c])
    best = np.full(len(X), np.inf)
    for c in ys:
        Y = np.array(c)
        P, D = Y[:-1], Y[1:] - Y[:-1]
        L = (D**2).sum(-1)
        L[L == 0] = 1e-12
        t = (((X[:, None, :] - P[None]) * D[None]).sum(-1) / L[None]).clip(0, 1)
        d = np.sqrt(((X[:, None, :] - (P[None] + t[..., None] * D[None])) ** 2).sum(-1))
        best = np.minimum(best, d.min(1))
    return float(best.max())


def at(font, place):
    axes = {a.axisTag: a.defaultValue for a in font["fvar"].axes}
    return instantiateVariableFont(font, {tag: place.get(tag, default) for tag, default in axes.items()})


def main():
    out = {}
    fonts = [TTFont(sys.argv[1]), TTFont(sys.argv[2])]
    for text in sys.argv[3].split(";"):
        place = {k: float(v) for k, v in (item.split("=") for item in text.split(","))}
        a, b = (at(f, place) for f in fonts)
        here = out[text] = {}
        for name in sys.argv[4:]:
            ca, wa, ba = samples(a, name)
            cb, wb, bb = samples(b, name)
            here[name] = {
                "distance": max(one_sided(ca, cb), one_sided(cb, ca)),
                "contours": [len(ca), len(cb)],
                "advance": [wa, wb],
                "width": [ba[2] - ba[0], bb[2] - bb[0]],
            }
    print(json.dumps(out))


if __name__ == "__main__":
    main()
