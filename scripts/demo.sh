#!/bin/sh
# Renders the demo animation (scenes/demo) with frame coherence on a local PVM virtual
# machine (fc-master starts and stops a private pvmd) into out/demo/, plus a contact sheet.
set -eu

top=$(cd "$(dirname "$0")/.." && pwd)
scene_dir=$top/scenes/demo
out=$top/out/demo
bin=$top/build/bin

for program in fc-master fc-slave povray-fc; do
    [ -x "$bin/$program" ] || { echo "demo.sh: $bin/$program missing: run 'make' first" >&2; exit 1; }
done
mkdir -p "$out"
rm -f "$out"/demo*.tga  # render everything again (fc-master would resume otherwise)

# Sequence division: each slave renders consecutive frames, so fc reuses pixels.
"$bin/fc-master" --division sequence --stats "$out/stats.json" \
    "$scene_dir/demo.ini" "+I$scene_dir/demo.pov" "+L$scene_dir" -o "$out"

frames=$(ls "$out"/demo*.tga | sort)
# shellcheck disable=SC2086 # one argument per frame file
oiiotool $frames --mosaic 6x4 --resize 50% -o "$out/contact-sheet.png"
echo "demo: $(echo "$frames" | wc -l) frames in $out, contact sheet $out/contact-sheet.png, statistics $out/stats.json"
