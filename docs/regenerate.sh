#!/bin/sh
# Regenerates the README images from the bundled typeface in glyphs/:
#   docs/sheet.png  every glyph with its metric guides (120 px cells, 12 per row)
#   docs/proof.png  the default proof text at 12-48 px per em
#   docs/studio.png the studio (xglyph serve) in headless Chromium
# Usage (from anywhere in the repository): sh docs/regenerate.sh. The PNGs need only Rust;
# studio.png also needs Chromium (its pixels may vary with the installed fonts and version).
# The output is deterministic: an unchanged glyphs/ gives byte-identical images.
# Re-run and commit the images whenever glyphs/ changes. Each image stays well under
# 300 KB for the full character set (about 215 KB and 130 KB).
set -eu
cd "$(dirname "$0")/.."
cargo run --release --quiet -- render glyphs --out docs \
    --cell 120 --columns 12 --sizes 12,16,24,36,48 --width 1400
# docs/studio.png: the studio's glyph editor, screenshotted by headless Chromium
# (/usr/bin/chromium, driven over the DevTools protocol by the same code as the browser test).
XGLYPH_REQUIRE_TOOLS=1 cargo test --quiet --test it studio_browser::screenshot -- --ignored --exact
