#!/usr/bin/env bash
# Reproduces the numbers and pictures of docs/memory.md with the omninav program only:
#   - Figs. 5, 6 and 7 of Menegatti et al. 2004 on a rendered 30 cm grid of the built-in
#     room (omninav export --what figures);
#   - localisation of random poses between the grid points in three rooms (seeds 1, 2, 3 of
#     worlds.yaml's room): colour per channel against luminance, against the number of
#     components m, and under an exposure change with raw and normalised magnitudes;
#   - figures like Figs. 8-10 for three queries.
# Everything is rendered and written under OUT (default: BUILD/memory_figures); nothing goes
# into the source tree. About 30 minutes on one core, most of it rendering three rooms.
#
# Usage: scripts/memory_figures.sh [BUILD_DIR] [OUT_DIR]
set -euo pipefail

here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$here/build}"
out="${2:-$build/memory_figures}"
omninav="$build/bin/omninav"
[ -x "$omninav" ] || { echo "no $omninav: build the omninav target first" >&2; exit 1; }
mkdir -p "$out/figures"

grid="grid:nx=10,ny=8,spacing_m=0.3"  # 270 x 210 cm, the grid of Menegatti et al. 2004, §3.3 (Fig. 14)
walk="walk:x=1.85,y=1.55,steps=400,step_m=0.23,turn_deg=150"
components="1 2 3 5 8 15 30 60 181"  # 181 = all of a 360-column row

# "localised N queries: P% within ..., Q% at the nearest place, ..." -> "N P Q"
score() {
  sed -n 's/^localised \([0-9]*\) quer[a-z]*: \([0-9.]*\)%.*, \([0-9.]*\)% at the nearest.*/\1 \2 \3/p' |
    head -n 1
}

for seed in 1 2 3; do
  dir="$out/seed$seed"
  config="$dir/config"
  rm -rf "$config"
  mkdir -p "$dir"
  cp -r "$here/config" "$config"
  # The room's layout and textures (worlds.yaml room.seed; the render seed stays 1).
  sed -i "s/^  seed: 1 \( *# random seed of the layout\)/  seed: $seed\1/" "$config/worlds.yaml"
  run() { "$omninav" -q --config-dir "$config" "$@"; }
  run render --trajectory "$grid" --out "$dir/grid" --force > /dev/null
  # Queries: a random walk with long steps and sharp turns, so that positions and headings are
  # spread; those off the grid (farther than half a cell diagonal from every place) are not
  # scored. A second copy rendered 1.25x brighter with pixel noise.
  run render --trajectory "$walk,seed=$seed" --out "$dir/queries" --force > /dev/null
  run render --trajectory "$walk,seed=$seed" --out "$dir/queries_exposure" --exposure 1.25 \
    --noise 4 --force > /dev/null
  for colour in luminance per_channel; do
    for brightness in normalised raw; do
      map="$dir/${colour}_$brightness.vmem"
      run explore --input "$dir/grid" --out "$map" --colour "$colour" --brightness "$brightness" \
        --components 181 --force > /dev/null
      for queries in queries queries_exposure; do
        "$omninav" --config-dir "$config" localise "$map" "$dir/$queries" --format csv \
          > "$dir/localise_${colour}_${brightness}_$queries.csv" 2> "$dir/summary.txt"
        echo "$seed $colour $brightness $queries $(score < "$dir/summary.txt")" >> "$out/scores.txt"
      done
      if [ "$brightness" = normalised ]; then
        for m in $components; do
          "$omninav" --config-dir "$config" localise "$map" "$dir/queries" --levels "$m" \
            --format csv > /dev/null 2> "$dir/summary.txt"
          echo "$seed m=$m $colour $(score < "$dir/summary.txt")" >> "$out/components.txt"
        done
      fi
    done
  done
  # The default map of the room (memory.yaml: luminance, normalised, m = 15) for the figures.
  run explore --input "$dir/grid" --out "$dir/default.vmem" --force > /dev/null
done

# Pooled over the three rooms: Σ N·P / Σ N, for both shares.
pool() {
  awk '{k = $1; for (i = 2; i <= NF - 3; ++i) k = k " " $i;
        n[k] += $(NF-2); w[k] += $(NF-2) * $(NF-1); e[k] += $(NF-2) * $NF}
       END {for (k in n) printf "%s: %.1f%% within one spacing, %.1f%% at the nearest place (%d queries)\n",
                                 k, w[k] / n[k], e[k] / n[k], n[k]}'
}
{
  echo "== within one grid spacing, pooled over rooms 1-3 (colour, brightness, queries)"
  cut -d' ' -f2- "$out/scores.txt" | pool | sort
  echo "== against the number of components m (normalised brightness)"
  cut -d' ' -f2- "$out/components.txt" | pool | sort -t= -k2 -n
} > "$out/summary.txt"
rm -f "$out/scores.txt" "$out/components.txt"

# Figs. 5-7 from the first room (the figures re-read the images and compute raw spectra of
# both colour modes).
"$omninav" export "$out/seed1/default.vmem" --what figures --out "$out/figures" \
  >> "$out/summary.txt"

# Figs. 8-10: three queries in the first room, at known poses between grid points.
printf 'x_m,y_m,heading_deg\n1.25,0.95,30\n2.45,1.85,-120\n0.65,2.35,75\n' > "$out/fig9_poses.csv"
"$omninav" -q render --trajectory "csv:path=$out/fig9_poses.csv" --out "$out/fig9_queries" \
  --force > /dev/null
"$omninav" -q localise "$out/seed1/default.vmem" "$out/fig9_queries" \
  --plot "$out/figures/fig9_localisation.png" > "$out/figures/fig9_localisation.txt"

cat "$out/summary.txt"
echo "pictures and data in $out/figures"
