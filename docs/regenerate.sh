#!/bin/sh
# Regenerates the README images from the bundled typeface in glyphs/:
#   docs/sheet.png  every glyph with its metric guides (120 px cells, 12 per row)
#   docs/proof.png  the default proof text at 12-48 px per em
# Usage (from anywhere in the repository, needs only Rust): sh docs/regenerate.sh
# The output is deterministic: an unchanged glyphs/ gives byte-identical images.
# Re-run and commit the images whenever glyphs/ changes. Each image stays well under
# 300 KB for the full character set (about 215 KB and 130 KB).
set -eu
cd "$(dirname "$0")/.."
cargo run --release --quiet -- render glyphs --out docs \
    --cell 120 --columns 12 --sizes 12,16,24,36,48 --width 1400
