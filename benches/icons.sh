#!/usr/bin/env bash
# SVG import speed on an icon set: `xglyph import` of the first N drawings (sorted by
# name) of a folder of SVG icons, on one thread (CPU seconds per icon).
#
#   benches/icons.sh DIR [N] [REFERENCE_XGLYPH]
#
# Icon sets are not in the repository; npm has them, e.g.
#   npm install @tabler/icons   # then DIR = node_modules/@tabler/icons/icons/outline
# Stroked outline icons are the demanding case: each stroke becomes a filled outline of
# many short curves (round caps and joins), fitted as long smooth stretches. With a
# reference binary, it is timed in the same run and both reports' point counts and largest
# errors are printed. Skips with a notice when DIR holds no SVG files.
set -euo pipefail
cd "$(dirname "$0")/.."
DIR=${1:?usage: benches/icons.sh DIR [N] [REFERENCE_XGLYPH]}
N=${2:-300}
REF=${3:-}
mapfile -t FILES < <(find "$DIR" -maxdepth 1 -name '*.svg' | sort | head -n "$N")
if [ "${#FILES[@]}" = 0 ]; then
    echo "skipped: no SVG files in $DIR"
    exit 0
fi
cargo build --release --quiet
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

# CPU seconds (user + system) of one import on one thread; its report's total line.
run() {
    local bin=$1 out=$2
    /usr/bin/env time -f "%U %S" -o "$WORK/time" env RAYON_NUM_THREADS=1 \
        "$bin" import "${FILES[@]}" -o "$out" >"$WORK/report"
    awk '{ printf "%.3f", $1 + $2 }' "$WORK/time"
    echo " $(grep '^total:' "$WORK/report")"
}

echo "icons: ${#FILES[@]} SVG drawings from $DIR (1 thread)"
new=$(run target/release/xglyph "$WORK/new")
echo "new:       ${new%% *} s CPU (${new#* })"
if [ -n "$REF" ]; then
    ref=$(run "$REF" "$WORK/ref")
    echo "reference: ${ref%% *} s CPU (${ref#* })"
    awk -v r="${ref%% *}" -v n="${new%% *}" 'BEGIN { printf "ratio (reference / new): %.2fx CPU\n", r / n }'
fi
