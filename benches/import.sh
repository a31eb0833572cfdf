#!/usr/bin/env bash
# Import speed on CJK outlines: `xglyph import` of the 64 glyphs U+4E00–U+4E3F of
# WenQuanYi Zen Hei (Debian fonts-wqy-zenhei; skipped with a notice when not installed).
#
#   benches/import.sh [REFERENCE_XGLYPH | GIT_REVISION]
#
# Builds the release binary, then times it on one thread (CPU seconds per glyph) and on
# every core (wall time). With a reference binary, or a git revision to build one from
# (e.g. `93bde19`, the original importer: built from `git archive` in a temporary folder
# with this worktree's target/, so only the xglyph crate compiles), times that one in the
# same run and prints the ratios; both outputs are also compared for point counts and the
# largest error from their reports.
#
#   benches/import.sh --variable
#
# Import of a variable font (issue 16, item 6): builds the bundled family's variable TTF,
# imports it (two masters fitted with one structure per glyph), and in the same run imports
# its default and Bold instances alone (fontTools `varLib.instancer`, the same outlines as
# static fonts); prints CPU seconds on one thread and X-spline points of each, and the
# ratios, and checks that 1 and 2 threads write identical files.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" = "--variable" ]; then
    cargo build --release --quiet
    WORK=$(mktemp -d)
    trap 'rm -rf "$WORK"' EXIT
    BIN=target/release/xglyph
    "$BIN" build glyphs -o "$WORK/built" >/dev/null
    VF="$WORK/built/XglyphSans[wght].ttf"
    fonttools varLib.instancer "$VF" wght=400 -q -o "$WORK/regular.ttf"
    fonttools varLib.instancer "$VF" wght=700 -q -o "$WORK/bold.ttf"
    # cpu INPUT OUT THREADS: CPU seconds (user + system) of one import; keeps its report.
    cpu() {
        rm -rf "$WORK/$2"
        { TIMEFORMAT='%U %S'; time RAYON_NUM_THREADS=$3 "$BIN" import "$1" -o "$WORK/$2" >"$WORK/$2.txt" 2>/dev/null; } 2>&1 |
            awk '{ printf "%.2f\n", $1 + $2 }'
    }
    points() { grep '^total' "$WORK/$1.txt" | head -1 | sed 's/.* \([0-9]*\) X-spline points.*/\1/'; }
    vf=$(cpu "$VF" vf 1)
    regular=$(cpu "$WORK/regular.ttf" regular 1)
    bold=$(cpu "$WORK/bold.ttf" bold 1)
    cpu "$VF" vf2 2 >/dev/null
    echo "variable font, 2 masters: $vf s CPU, $(points vf) points per master"
    echo "Regular alone: $regular s CPU, $(points regular) points"
    echo "Bold alone:    $bold s CPU, $(points bold) points"
    # The most demanding master per glyph: the larger of the two static counts.
    most=$(paste <(awk 'NF == 4 && $2 ~ /^[0-9]+$/ { print $3 }' "$WORK/regular.txt") \
                 <(awk 'NF == 4 && $2 ~ /^[0-9]+$/ { print $3 }' "$WORK/bold.txt") |
           awk '{ s += ($1 > $2 ? $1 : $2) } END { print s }')
    echo "per glyph, the larger static count: $most points"
    echo "ratios: points $(echo "scale=3; $(points vf) / $(points regular)" | bc)x Regular alone, $(echo "scale=3; $(points vf) / $most" | bc)x the larger per glyph; CPU $(echo "scale=2; $vf / ($regular + $bold)" | bc)x both static imports"
    if diff -rq "$WORK/vf" "$WORK/vf2" >/dev/null; then
        echo "1 thread and 2 threads: identical files"
    else
        echo "1 thread and 2 threads: FILES DIFFER"
        exit 1
    fi
    exit 0
fi
FONT=/usr/share/fonts/truetype/wqy/wqy-zenhei.ttc
GLYPHS='一-丿'
COUNT=64
if [ ! -f "$FONT" ]; then
    echo "skipped: $FONT is not installed (apt-get install fonts-wqy-zenhei)"
    exit 0
fi
cargo build --release --quiet
REF=${1:-}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
NEW=$WORK/xglyph-new
cp target/release/xglyph "$NEW"
if [ -n "$REF" ] && [ ! -x "$REF" ]; then
    git rev-parse --verify --quiet "$REF^{commit}" >/dev/null || {
        echo "error: $REF is neither an executable nor a git revision" >&2
        exit 2
    }
    mkdir "$WORK/ref-src"
    git archive "$REF" | tar -x -C "$WORK/ref-src"
    TARGET=$(pwd)/target
    (cd "$WORK/ref-src" && CARGO_TARGET_DIR="$TARGET" cargo build --release --quiet --offline --bin xglyph)
    cp "$TARGET/release/xglyph" "$WORK/xglyph-ref"
    # The reference build replaced target/release/xglyph: the next build links it again.
    touch src/main.rs
    REF=$WORK/xglyph-ref
fi
# The reference may predate .ttc input: give both the collection's first font as .ttf.
python3 - "$FONT" "$WORK/wqy.ttf" <<'PY' 2>/dev/null || cp "$FONT" "$WORK/wqy.ttc"
import sys
from fontTools.ttLib import TTCollection
TTCollection(sys.argv[1]).fonts[0].save(sys.argv[2])
PY
INPUT=$WORK/wqy.ttf
[ -f "$INPUT" ] || INPUT=$WORK/wqy.ttc

# run BINARY THREADS LABEL: prints "cpu_seconds wall_seconds" and keeps the report.
run() {
    local out="$WORK/out-$3"
    rm -rf "$out"
    local t0 t1
    t0=$(date +%s.%N)
    local cpu
    cpu=$( { TIMEFORMAT='%U %S'; time RAYON_NUM_THREADS=$2 "$1" import "$INPUT" --glyphs "$GLYPHS" -o "$out" >"$WORK/report-$3" 2>/dev/null; } 2>&1 )
    t1=$(date +%s.%N)
    echo "$cpu" | awk -v w="$(echo "$t1 - $t0" | bc)" '{ printf "%.3f %.3f\n", $1 + $2, w }'
}

# The new importer takes a fraction of a second on one thread, a few ticks of the 10 ms
# CPU clock: the mean of five runs (the reference takes seconds: one run).
new_cpu=0
for _ in 1 2 3 4 5; do
    read -r cpu _ < <(run "$NEW" 1 new1)
    new_cpu=$(echo "scale=4; $new_cpu + $cpu / 5" | bc)
done
read -r _ new_wall < <(run "$NEW" 0 new)
echo "new:       $(echo "scale=2; 1000 * $new_cpu / $COUNT" | bc) ms CPU per glyph (1 thread), $new_wall s wall on $(nproc) cores"
grep '^total' "$WORK/report-new"
if [ -n "$REF" ]; then
    read -r ref_cpu ref_wall < <(run "$REF" 1 ref)
    echo "reference: $(echo "scale=2; 1000 * $ref_cpu / $COUNT" | bc) ms CPU per glyph, $ref_wall s wall"
    grep '^total' "$WORK/report-ref"
    echo "ratio (reference / new): $(echo "scale=1; $ref_cpu / $new_cpu" | bc)x CPU per glyph, $(echo "scale=1; $ref_wall / $new_wall" | bc)x wall"
fi
if cmp -s <(cd "$WORK/out-new1" && cat ./*.toml) <(cd "$WORK/out-new" && cat ./*.toml); then
    echo "1 thread and $(nproc) threads: identical files"
else
    echo "1 thread and $(nproc) threads: FILES DIFFER"
    exit 1
fi
