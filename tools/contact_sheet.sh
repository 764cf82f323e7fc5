#!/usr/bin/env bash
# Renders every glTF/GLB model under MODEL_DIR (each MODEL_DIR/NAME/*.gltf|*.glb, or
# MODEL_DIR/*.gltf|*.glb) at SIZE x SIZE with the models' own camera and lights (else the
# default view and lighting) and lays the renders out, each named, as one contact sheet.
# One gridrt at a time; per model its exit code, time and warnings go to OUT.log.
#
#   tools/contact_sheet.sh MODEL_DIR OUT.png [SIZE=256] [COLUMNS=6]
#
# Used to look over the Khronos glTF sample models (docs/gltf.md, "Sample models").
set -uo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
if [ $# -lt 2 ] || [ "$1" = "--help" ] || [ "$1" = "-h" ]; then
  sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//'
  [ $# -lt 2 ] && [ "${1:-}" != "--help" ] && [ "${1:-}" != "-h" ] && exit 2
  exit 0
fi
models=$1 out=$2 size=${3:-256} columns=${4:-6}
[ -d "$models" ] || { echo "contact_sheet: no folder '$models'" >&2; exit 2; }
command -v oiiotool >/dev/null || { echo "contact_sheet: oiiotool missing (openimageio-tools)" >&2; exit 1; }
gridrt=${GRIDRT:-$root/build/gridrt}  # the renderer to run (a test passes its own build)
[ -x "$gridrt" ] || { echo "contact_sheet: $gridrt missing: run tools/setup.sh" >&2; exit 1; }
renders=$(mktemp -d)
trap 'rm -rf "$renders"' EXIT
log="${out%.*}.log"
: > "$log"
font=/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf
args=()
while IFS= read -r model; do
  name=$(basename "$model"); name=${name%.*}
  start=$(date +%s.%N)
  "$gridrt" "$model" --width "$size" --height "$size" -o "$renders/$name.png" --force \
    2> "$renders/$name.err"
  rc=$?
  seconds=$(python3 -c "print(round($(date +%s.%N) - $start, 2))")
  printf '%s\texit %s\t%s s\t%s\n' "$name" "$rc" "$seconds" \
    "$(grep -E 'warning|error' "$renders/$name.err" | tr '\n' ' ')" >> "$log"
  [ "$rc" -eq 0 ] || oiiotool --create "${size}x${size}" 3 -o "$renders/$name.png"
  args+=("$renders/$name.png" --ch R,G,B --cut "0,0,$((size - 1)),$((size + 15))")
  [ -f "$font" ] && args+=(--text:x=4:y=$((size + 12)):size=14:font=$font "$name")
done < <(find "$models" -maxdepth 2 \( -name '*.gltf' -o -name '*.glb' \) | sort)
count=$(wc -l < "$log")
[ "$count" -gt 0 ] || { echo "contact_sheet: no .gltf or .glb under '$models'" >&2; exit 1; }
rows=$(( (count + columns - 1) / columns ))
oiiotool "${args[@]}" --mosaic:pad=4 "${columns}x${rows}" -o "$out" || exit 1
echo "contact_sheet: $count models -> $out (log: $log)"
