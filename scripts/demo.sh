#!/bin/sh
# Renders the demo animation (scenes/demo) into out/demo/ and a contact sheet of it.
set -eu

top=$(cd "$(dirname "$0")/.." && pwd)
scene_dir=$top/scenes/demo
out=$top/out/demo
povray=$top/build/bin/povray-fc

[ -x "$povray" ] || { echo "demo.sh: $povray missing: run 'make' first" >&2; exit 1; }
mkdir -p "$out"

# POV-Ray's I/O restrictions allow writing only below the working directory and
# /tmp, so render from the output directory with the scene named absolutely.
cd "$out"
"$povray" "$scene_dir/demo.ini" "+I$scene_dir/demo.pov" "+O$out/demo" -D -P -V

frames=$(ls "$out"/demo*.tga | sort)
# shellcheck disable=SC2086 # one argument per frame file
oiiotool $frames --mosaic 6x4 --resize 50% -o "$out/contact-sheet.png"
echo "demo: $(echo "$frames" | wc -l) frames in $out, contact sheet $out/contact-sheet.png"
