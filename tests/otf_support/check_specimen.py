#!/usr/bin/env python3
"""Reads the `<output id="font-check">` of a specimen page from Chromium's --dump-dom.

Usage: check_specimen.py DOM_FILE LABEL

The page's script writes data-loaded ("yes" once the @font-face font loaded) and
data-width (the measured width of a line set at one CSS pixel per font unit) next to
data-expected (the sum of the model's advances and kerning for that line). A fallback
font, a font the browser rejected, or missing kerning all change the width. Exits 1 with
a message unless the font loaded and the widths agree within 0.5 px + 0.01 % (Chromium
positions glyphs in fixed point: 22163 px of text measured 22162.969 px; a fallback font
is off by whole percents).
"""

import re
import sys

TOLERANCE_PX = 0.5
TOLERANCE_RELATIVE = 1e-4


def main():
    dom_file, label = sys.argv[1], sys.argv[2]
    with open(dom_file, encoding="utf-8", errors="replace") as f:
        dom = f.read()
    m = re.search(r'<output id="font-check"([^>]*)>', dom)
    if not m:
        print(f"check-fonts: chromium: {label}: no font-check output in the page")
        return 1
    attrs = dict(re.findall(r'([\w-]+)="([^"]*)"', m.group(1)))
    loaded = attrs.get("data-loaded")
    if loaded != "yes":
        print(f"check-fonts: chromium: {label}: font not loaded (data-loaded={loaded!r})")
        return 1
    try:
        width = float(attrs["data-width"])
        expected = float(attrs["data-expected"])
    except (KeyError, ValueError):
        print(f"check-fonts: chromium: {label}: no measured width ({attrs})")
        return 1
    if abs(width - expected) > TOLERANCE_PX + TOLERANCE_RELATIVE * expected:
        print(f"check-fonts: chromium: {label}: text width {width} px, expected {expected} px "
              f"from the font's advances and kerning (fallback font?)")
        return 1
    print(f"check-fonts: chromium: {label}: font loaded, text width {width} px, "
          f"expected {expected} px")
    return 0


if __name__ == "__main__":
    sys.exit(main())
