#!/usr/bin/env bash
# Makes the seed maps of tests/fuzz/corpus/map/ with a built omninav (default build/bin/omninav):
# small valid maps for the map loader's fuzzer to mutate. Tiny panoramas (32 x 4 pixels) and
# two Fourier components keep the signatures at 64 bytes a place, and SQLite pages of 512
# bytes keep each map a few kilobytes: a mutation of a small file more often hits something.
#
#   tests/fuzz/make_map_seeds.sh [path/to/omninav]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
omninav=${1:-$root/build/bin/omninav}
out=$root/tests/fuzz/corpus/map
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

cp -r "$root/config" "$scratch/config"
sed -i 's/^  width_px: 360/  width_px: 32/; s/^  height_px: 45/  height_px: 4/' \
  "$scratch/config/camera.yaml"
sed -i 's/^  components: 15 /  components: 2 /; s/^  thumbnail_width_px: 180/  thumbnail_width_px: 8/' \
  "$scratch/config/memory.yaml"
run() { "$omninav" --config-dir "$scratch/config" -q "$@"; }

# A route of 4 places with truth and headings, then the same map with a lattice.
run render --trajectory "line:x0=1,y0=1,x1=2.2,y1=1.3,speed_m_s=0.4,fps=1" --out "$scratch/line"
run explore --input "$scratch/line" --out "$scratch/route.vmem" --heading-source truth \
  --every-n-frames 1
cp "$scratch/route.vmem" "$scratch/organised.vmem"
run organise "$scratch/organised.vmem" --step-m 0.4
# A grid of 2 x 2 places (grid edges, no stream).
run render --trajectory "grid:nx=2,ny=2,spacing_m=0.5,x0=1,y0=1" --out "$scratch/grid"
run explore --input "$scratch/grid" --out "$scratch/grid.vmem"

mkdir -p "$out"
for map in route organised grid; do
  python3 - "$scratch/$map.vmem" "$out/$map.vmem" <<'PYTHON'
import shutil, sqlite3, sys
db = sqlite3.connect(sys.argv[1])
db.execute("PRAGMA page_size = 512")
db.execute("VACUUM")
db.close()
shutil.copyfile(sys.argv[1], sys.argv[2])
PYTHON
done
ls -l "$out"
