#!/usr/bin/env python3
"""A stand-in for `xglyph import` on WenQuanYi Zen Hei, for timing `build` alone.

Writes an xglyph source folder with one glyph per code point of U+4E00..U+9FA5 (20,902),
taking each TrueType contour's points as they are: on-curve points become sharp points
(s = 0), off-curve points approximating points (s = 1), so a quadratic arc becomes an
X-spline arc of the same control polygon. The shapes are close to the font's, not within a
tolerance of them (that is the importer's job); the point counts are those of the font,
which bound what a real import produces. Needs fontTools.

Usage: cjk_standin.py FONT.ttc OUT_DIR [FIRST LAST]   (hex code points, default 4E00 9FA5)
"""
import os
import sys

from fontTools.ttLib import TTCollection, TTFont


def main():
    font_path, out = sys.argv[1], sys.argv[2]
    first = int(sys.argv[3], 16) if len(sys.argv) > 3 else 0x4E00
    last = int(sys.argv[4], 16) if len(sys.argv) > 4 else 0x9FA5
    font = TTCollection(font_path).fonts[0] if font_path.endswith(".ttc") else TTFont(font_path)
    cmap = font.getBestCmap()
    glyf = font["glyf"]
    hmtx = font["hmtx"]
    upm = font["head"].unitsPerEm
    os2 = font["OS/2"]
    os.makedirs(out, exist_ok=False)
    with open(os.path.join(out, "font.toml"), "w") as f:
        f.write('family = "WenQuanYi Zen Hei Standin"\nstyle = "Regular"\n')
        f.write(f"units_per_em = {upm}\nascender = {font['hhea'].ascent}\n")
        f.write(f"descender = {font['hhea'].descent}\n")
        f.write(f"x_height = {getattr(os2, 'sxHeight', 0) or upm // 2}\n")
        f.write(f"cap_height = {getattr(os2, 'sCapHeight', 0) or upm * 7 // 10}\n")
        f.write("tolerance = 0.5\n")
    written = 0
    for cp in range(first, last + 1):
        name = cmap.get(cp)
        if name is None:
            continue
        g = glyf[name]
        contours = []
        if g.numberOfContours > 0:
            coords, ends, flags = g.getCoordinates(glyf)
            start = 0
            for end in ends:
                pts = []
                for i in range(start, end + 1):
                    x, y = coords[i]
                    s = 0 if flags[i] & 1 else 1
                    if pts and (pts[-1][0], pts[-1][1]) == (x, y):
                        continue
                    pts.append((x, y, s))
                while len(pts) > 1 and pts[0][:2] == pts[-1][:2]:
                    pts.pop()
                # Slivers (collinear or out-and-back polygons) enclose nothing; `check`
                # refuses them, the font's rasteriser ignores them.
                area = sum(
                    pts[i - 1][0] * pts[i][1] - pts[i][0] * pts[i - 1][1] for i in range(len(pts))
                )
                if len(pts) >= 3 and abs(area) >= 100:
                    contours.append(pts)
                start = end + 1
        with open(os.path.join(out, f"uni{cp:04X}.toml"), "w") as f:
            f.write(f'name = "uni{cp:04X}"\nunicode = 0x{cp:04X}\nadvance = {hmtx[name][0]}\n')
            for pts in contours:
                body = ", ".join(f"[{x}, {y}, {s}]" for x, y, s in pts)
                f.write(f"\n[[contour]]\npoints = [{body}]\n")
        written += 1
    print(f"wrote {written} glyphs to {out}")


if __name__ == "__main__":
    main()
