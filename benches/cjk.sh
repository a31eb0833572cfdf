#!/bin/sh
# CJK scale benchmark (issue 15, item 4): import the CJK Unified Ideographs block
# U+4E00..U+9FA5 (20,902 glyphs) from WenQuanYi Zen Hei and build every output.
#
# Reports: import time; `build` wall time on 2 threads (cold: no cache; warm: nothing
# changed; incremental: one glyph edited), peak memory (/usr/bin/time -v), the sheet pages,
# and the limits: import < 60 s, build < 20 s, peak memory < 2 GB, incremental < 2 s.
# Skips with a notice when the font (Debian's fonts-wqy-zenhei) or /usr/bin/time is missing;
# CI does not run it.
#
# Usage: sh benches/cjk.sh [WORK_DIR]      (default: target/cjk-bench; wiped first)
# Environment:
#   CJK_IMPORT_TIMEOUT=S  give up on the import after S seconds (default 900)
#   XGLYPH_BIN=PATH       time this binary instead of building target/release/xglyph
#   CJK_SRC=DIR           skip the import: copy this already imported source folder into
#                         WORK_DIR (DIR itself is never edited) and build the copy
#   CJK_STANDIN=1         if the import fails or times out, build a stand-in source folder
#                         with benches/cjk_standin.py (fontTools: the font's own control
#                         points as X-spline points) so that the build figures are still
#                         measured; the report says so.
set -eu
cd "$(dirname "$0")/.."
FONT=/usr/share/fonts/truetype/wqy/wqy-zenhei.ttc
if [ ! -f "$FONT" ]; then
    echo "cjk.sh: skipped: $FONT is missing (apt-get install fonts-wqy-zenhei)"
    exit 0
fi
if [ ! -x /usr/bin/time ]; then
    echo "cjk.sh: skipped: /usr/bin/time is missing (apt-get install time)"
    exit 0
fi
WORK=${1:-target/cjk-bench}
rm -rf "$WORK"
mkdir -p "$WORK"
if [ -n "${XGLYPH_BIN:-}" ]; then
    BIN=$XGLYPH_BIN
else
    cargo build --release --quiet
    BIN=$(pwd)/target/release/xglyph
fi
SRC=$WORK/src
OUT=$WORK/out

# Runs a command under /usr/bin/time -v; sets WALL (s), CPU (user + system s) and PEAK_MB.
timed() {
    log=$WORK/time.log
    status=0
    /usr/bin/time -v "$@" >"$WORK/cmd.out" 2>"$log" || status=$?
    WALL=$(awk -F': ' '/Elapsed \(wall clock\)/ {
        n = split($2, t, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + t[i]; print s }' "$log")
    PEAK_MB=$(awk -F': ' '/Maximum resident set size/ { printf "%.0f", $2 / 1024 }' "$log")
    CPU=$(awk -F': ' '/(User|System) time/ { s += $2 } END { printf "%.1f", s }' "$log")
    return $status
}

verdict() { # value limit
    awk -v v="$1" -v l="$2" 'BEGIN { print (v < l) ? "ok" : "OVER" }'
}

echo "cjk.sh: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg)"

# 1. Import (the .ttc's first face).
IMPORT_NOTE=""
if [ -n "${CJK_SRC:-}" ]; then
    cp -r "$CJK_SRC" "$SRC"
    WALL=0; PEAK_MB=0
    IMPORT_WALL=0; IMPORT_PEAK=0
    IMPORT_NOTE="skipped: a copy of $CJK_SRC"
elif timed timeout "${CJK_IMPORT_TIMEOUT:-900}" "$BIN" import "$FONT" --glyphs '一-龥' -o "$SRC"; then
    IMPORT_WALL=$WALL
    IMPORT_PEAK=$PEAK_MB
    IMPORT_NOTE="$(tail -n 3 "$WORK/cmd.out" | tr '\n' ' ')"
else
    IMPORT_WALL=$WALL
    IMPORT_PEAK=$PEAK_MB
    IMPORT_NOTE="FAILED or timed out after ${WALL} s: $(tail -n 2 "$WORK/time.log" | head -n 1)"
    if [ "${CJK_STANDIN:-0}" = 1 ]; then
        rm -rf "$SRC"
        python3 benches/cjk_standin.py "$FONT" "$SRC" >/dev/null
        IMPORT_NOTE="$IMPORT_NOTE; build figures below are on the fontTools stand-in"
    else
        echo "import: $IMPORT_NOTE"
        echo "(set CJK_STANDIN=1 to measure the build on a stand-in source folder)"
        exit 1
    fi
fi
GLYPHS=$(ls "$SRC"/*.toml | grep -vc '/font.toml$\|/kerning.toml$' || true)

# 2. Build: cold (no cache), warm (nothing changed), one glyph edited.
export RAYON_NUM_THREADS=2
timed "$BIN" build "$SRC" -o "$OUT"
COLD=$WALL; COLD_PEAK=$PEAK_MB; COLD_CPU=$CPU
SUMMARY=$(head -n 2 "$WORK/cmd.out")
timed "$BIN" build "$SRC" -o "$OUT"
WARM=$WALL; WARM_PEAK=$PEAK_MB; WARM_CPU=$CPU
# Move the first point of one glyph by one unit.
EDIT=$SRC/$(ls "$SRC" | grep -v '^font.toml$' | sed -n 100p)
python3 - "$EDIT" <<'PY'
import re, sys
path = sys.argv[1]
text = open(path).read()
text = re.sub(r"\[(-?\d+(?:\.\d+)?),", lambda m: "[" + repr(float(m.group(1)) + 1) + ",", text, count=1)
open(path, "w").write(text)
PY
timed "$BIN" build "$SRC" -o "$OUT"
EDITED=$WALL; EDITED_PEAK=$PEAK_MB; EDITED_CPU=$CPU

# 3. Sheet pages: count and the largest page (PNG header).
PAGES=$(ls "$OUT" | grep -c '^sheet.*\.png$')
LARGEST=$(python3 - "$OUT" <<'PY'
import os, struct, sys
best = (0, 0, "")
for name in os.listdir(sys.argv[1]):
    if name.startswith("sheet") and name.endswith(".png"):
        with open(os.path.join(sys.argv[1], name), "rb") as f:
            w, h = struct.unpack(">II", f.read(24)[16:24])
        best = max(best, (w * h, w, name, h))
print(f"{best[2]} {best[1]} x {best[3]} px")
PY
)
PEAK=$(printf '%s\n' "$COLD_PEAK" "$WARM_PEAK" "$EDITED_PEAK" "$IMPORT_PEAK" | sort -n | tail -n 1)

echo "import: $GLYPHS glyphs in $IMPORT_WALL s, peak $IMPORT_PEAK MB ($(verdict "$IMPORT_WALL" 60); limit 60 s) $IMPORT_NOTE"
echo "$SUMMARY"
echo "build, 2 threads, cold (no cache):   $COLD s ($COLD_CPU CPU-s), peak $COLD_PEAK MB ($(verdict "$COLD" 20); limit 20 s)"
echo "build, 2 threads, warm (no change):  $WARM s ($WARM_CPU CPU-s), peak $WARM_PEAK MB"
echo "build, 2 threads, one glyph edited:  $EDITED s ($EDITED_CPU CPU-s), peak $EDITED_PEAK MB ($(verdict "$EDITED" 2); limit 2 s; edited $(basename "$EDIT"))"
echo "load average after the builds: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "peak memory: $PEAK MB ($(verdict "$PEAK" 2048); limit 2048 MB)"
echo "sheet: $PAGES pages, largest $LARGEST"
