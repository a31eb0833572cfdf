#!/bin/sh
# Regenerates the README images from the bundled typeface in glyphs/:
#   docs/sheet.png  every glyph with its metric guides (120 px cells, 12 per row)
#   docs/proof.png  the default proof text at 12-48 px per em
#   docs/weights/   one proof line at each named instance (Regular 400 … Bold 700)
#   docs/bold/, docs/w550/  sheet and proof of the Bold master and of weight 550
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
# docs/weights/<wght>.png: one proof line at each named instance (the README's waterfall).
for w in 400 500 600 700; do
    tmp=$(mktemp -d)
    cargo run --release --quiet -- render glyphs --at "wght=$w" --out "$tmp" --only proof \
        --sizes 40 --width 1400 --text "Hamburgefonstiv AVATAR Quartz 0123456789 Ångström"
    mkdir -p docs/weights
    mv "$tmp/proof.png" "docs/weights/$w.png"
    rm -rf "$tmp"
done
for at in 700:bold 550:w550; do
    cargo run --release --quiet -- render glyphs --at "wght=${at%%:*}" --out "docs/${at#*:}" \
        --cell 120 --columns 12 --sizes 12,16,24,36,48 --width 1400
done
# docs/studio.png: the studio's glyph editor, screenshotted by headless Chromium
# (/usr/bin/chromium, driven over the DevTools protocol by the same code as the browser test).
XGLYPH_REQUIRE_TOOLS=1 cargo test --quiet --test it studio_browser::screenshot -- --ignored --exact
