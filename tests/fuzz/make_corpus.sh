#!/usr/bin/env bash
# Regenerates the seed corpus of the fuzz targets (tests/fuzz/corpus/).
# usage: tests/fuzz/make_corpus.sh BUILD_DIR   (a build with the unstack tool)
#
# structure/: the files of tests/data (valid and bad), small generated
#             structures and hand-written malformed ones (seed-*.json);
# pipeline/:  every valid seed behind control bytes that pick each search,
#             step size, kinematics and method (fuzz_pipeline.c);
# oom/:       a few valid seeds with failures armed in each phase.
# Findings kept as regression files (crash-*, named after what they found)
# are not touched.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
cli=${1:?usage: make_corpus.sh BUILD_DIR}/unstack
data=$here/../data
out=$here/corpus
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out/structure" "$out/pipeline" "$out/oom"
rm -f "$out"/structure/seed-* "$out"/pipeline/seed-* "$out"/oom/seed-*

# ---- structures: the test data, generated scenes, malformed texts
for f in "$data"/*.json; do cp "$f" "$out/structure/seed-data-$(basename "$f")"; done
for f in "$data"/bad/*.json; do cp "$f" "$out/structure/seed-bad-$(basename "$f")"; done
gen() { local name=$1; shift; "$cli" generate "$@" -o "$out/structure/seed-gen-$name.json"; }
gen column3 column --blocks 3
gen column8 column --blocks 8 --friction 0
gen pyramid3 pyramid --rows 3
gen pyramid5 pyramid --rows 5 --friction 0.2
gen wall3x3 wall --rows 3 --cols 3
gen arch5 arch --voussoirs 5
gen arch7loose arch --voussoirs 7 --loose 3
gen random4 random --rows 4 --width 4 --seed 3
gen stacker random --rows 3 --width 4 --seed 11
gen stacker4 stacker --rows 4 --width 5 --seed 2
gen heavy column --blocks 4 --density 1000 --friction 2
sd=$out/structure
printf '' > "$sd/seed-mal-empty.json"
printf '{' > "$sd/seed-mal-open.json"
printf '{"bodies": [{"id": "a", "polygon": [[0,0],[1,0],[1,1],[0,1]]}' > "$sd/seed-mal-cut.json"
printf '{"bodies": [{"id": "a", "polygon": [[0,0],[1,0],[1,1e308],[0,1]]}]}' > "$sd/seed-mal-huge.json"
printf '{"bodies": [{"id": "a\\u0000b", "polygon": [[0,0],[1,0],[1,1],[0,1]]}]}' > "$sd/seed-mal-nul-id.json"
printf '{"bodies": [{"id": "<&>\\"x\\uFFFE", "polygon": [[0,0],[1,0],[1,1],[0,1]]}]}' > "$sd/seed-mal-xml-id.json"
printf '{"bodies": [{"id": "a", "polygon": [[0,0],[2,2],[2,0],[0,2]]}]}' > "$sd/seed-mal-bowtie.json"
printf '{"gravity": [0, 0], "bodies": [{"id": "a", "polygon": [[0,0],[1,0],[1,1],[0,1]]}]}' > "$sd/seed-mal-no-gravity.json"
printf '{"friction": 1e300, "bodies": [{"id": "a", "polygon": [[0,0],[1,0],[1,1],[0,1]]}, {"id": "b", "polygon": [[0,1],[1,1],[1,2],[0,2]]}]}' > "$sd/seed-mal-friction.json"
printf '{"bodies": [{"id": "a", "center": [0.5, 0.5], "mass": 1}], "contacts": [{"a": "ground", "b": "a", "point": [0.5, 0], "normal": [0, 1]}]}' > "$sd/seed-point.json"
printf '\xef\xbb\xbf{"bodies": []}' > "$sd/seed-mal-bom.json"
printf '[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[' > "$sd/seed-mal-deep.json"

# ---- pipeline: control bytes + structure text
valid=()
for f in "$sd"/seed-*.json; do
  if "$cli" check "$f" >/dev/null 2>&1 || [ $? -eq 1 ]; then valid+=("$f"); fi
done
ctl() { printf "\\x$(printf %02x "$1")\\x$(printf %02x "$2")"; }
i=0
for f in "${valid[@]}"; do
  b=$(basename "$f" .json)
  b=${b#seed-}
  # cycle through the searches, step sizes, kinematics and methods
  c0=$(( (i * 37 + 1) % 256 )); c1=$(( (i * 53 + 3) % 256 ))
  [ $((i % 3)) -eq 0 ] && { ctl 0 0; cat "$f"; } > "$out/pipeline/seed-$b-assemble.json"
  { ctl "$c0" "$c1"; cat "$f"; } > "$out/pipeline/seed-$b-mix.json"
  i=$((i + 1))
done
# pyramid3 through every search and step size, the methods in turn
for s in 0 1 2 3; do
  for g in 0 2 3; do
    c0=$(( s | g << 2 | ((s + g) % 3) << 4 ))
    meth=$(( (s + g) % 4 ))
    { ctl "$c0" "$meth"; cat "$sd/seed-gen-pyramid3.json"; } \
      > "$out/pipeline/seed-pyramid3-s$s-g$g-m$meth.json"
  done
done

# box piles (a NUL byte, friction, then x/width/height bytes per box)
hex() { printf "$(printf '\\x%02x' "$@")"; }
hex 0 0 0 16  0 4 3  2 4 3  1 4 3 > "$out/pipeline/seed-boxes-column.bin"
hex 1 0 0 16  0 8 2  6 8 2  12 4 2 > "$out/pipeline/seed-boxes-dfs.bin"
hex 0 1 0 0   0 4 3  2 4 3  4 4 3  6 4 3 > "$out/pipeline/seed-boxes-mu0.bin"
hex 2 2 0 12  0 4 67  4 12 1  14 2 1  3 4 130 > "$out/pipeline/seed-boxes-cantilever.bin"
hex 3 3 0 32  0 4 1  4 4 1  2 4 1  6 4 1  4 4 1  8 4 1  1 6 2  7 6 2 > "$out/pipeline/seed-boxes-pile.bin"
hex 12 0 0 255  0 2 7  2 2 7  0 4 1  1 2 7 > "$out/pipeline/seed-boxes-sticky.bin"

# ---- oom: phase, N (little-endian), control bytes, structure
for f in "$sd/seed-gen-column3.json" "$sd/seed-gen-arch5.json" "$sd/seed-data-explicit.json"; do
  b=$(basename "$f" .json)
  b=${b#seed-}
  for phase in 0 1 2 3; do
    for n in 0 3 17 60; do
      { printf "\\x$(printf %02x $phase)\\x$(printf %02x $n)\\x00"; ctl $((phase * 37)) $phase; cat "$f"; } \
        > "$out/oom/seed-$b-p$phase-n$n.json"
    done
  done
done
for phase in 1 2 3; do
  for n in 5 40; do
    { hex $phase $n 0 $((phase * 37)) $phase; cat "$out/pipeline/seed-boxes-pile.bin"; } \
      > "$out/oom/seed-boxes-p$phase-n$n.bin"
  done
done
echo "corpus: $(ls "$out/structure" | wc -l) structure, $(ls "$out/pipeline" | wc -l) pipeline, $(ls "$out/oom" | wc -l) oom"
