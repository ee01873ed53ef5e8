#!/usr/bin/env bash
# Measures the compass on the saccadic route in every row of the full suite without the rest of
# the suite (docs/evaluation.md, "The compass on saccadic routes"): `omninav evaluate` on a copy
# of config/suites/full.yaml whose grid is cut to 2 x 2 points, 1 query and 1 trial. The compass
# routes do not depend on those (the layout's centre and circle depend on the world, the spacing
# and the robot's radius only), so every route, and its commands in commands.sh, are the full
# suite's; the memory, lattice and navigation cells of this run mean nothing.
#
#   scripts/compass_saccade.sh [work folder] [rows]   (default /tmp/omninav-compass-saccade, all)
#
# rows: evaluate's --worlds list (e.g. field-s1-h5cm,field-s2-h5cm). Environment: OMNINAV (the
# binary, default build/bin/omninav), CONFIG_DIR (default build/share/omninav/config). Writes
# <work folder>/compass.csv (the compass columns of evaluation.csv, every route of every row) and
# prints the saccadic route's columns as a Markdown table, then the worst row of each family.
# Deterministic. About 2.5 minutes a row on two shared cores.
set -euo pipefail

cd "$(dirname "$0")/.."
OMNINAV=${OMNINAV:-build/bin/omninav}
CONFIG_DIR=${CONFIG_DIR:-build/share/omninav/config}
WORK=${1:-/tmp/omninav-compass-saccade}
ROWS=${2:-}
mkdir -p "$WORK"
# One rendering thread: the machines this runs on are shared.
export OPENCV_FOR_THREADS_NUM=${OPENCV_FOR_THREADS_NUM:-1}

shared=$(cd config/suites && realpath -m ../../../shared)
sed -e 's/^name: full$/name: full-compass/' \
    -e 's/grid_nx: [0-9]*/grid_nx: 2/g; s/grid_ny: [0-9]*/grid_ny: 2/g' \
    -e 's/queries: [0-9]*/queries: 1/; s/trials: [0-9]*/trials: 1/' \
    -e "s|\.\./\.\./\.\./shared|$shared|" \
    config/suites/full.yaml > "$WORK/suite.yaml"

# Evaluates once into the work folder (kept: delete it to evaluate again). A row that fails
# leaves its cells empty and evaluate's exit status non-zero; the table says "failed".
if [ ! -f "$WORK/out/evaluation.csv" ]; then
  "$OMNINAV" --config-dir "$CONFIG_DIR" evaluate --suite "$WORK/suite.yaml" --out "$WORK/out" \
    ${ROWS:+--worlds "$ROWS"} > "$WORK/evaluate.log" 2>&1 || true
fi

python3 - "$WORK/out/evaluation.csv" "$WORK/compass.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
columns = ["world", "family"] + [k for k in rows[0] if k.startswith("compass_")]
with open(sys.argv[2], "w", newline="") as out:
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(columns)
    writer.writerows([row[k] for k in columns] for row in rows)
keys = ["compass_saccade_max_deg", "compass_saccade_mean_deg", "compass_saccade_end_deg"]
print("| world | family | max \\|e\\| (°) | mean e (°) | end e (°) |")
print("| --- | --- | ---: | ---: | ---: |")
worst = {}
for row in rows:
    cells = [row[k] for k in keys]
    print("| " + " | ".join([row["world"], row["family"]] +
                            [f"{float(c):.1f}" if c else "failed" for c in cells]) + " |")
    value = float(row[keys[0]]) if row[keys[0]] else float("inf")
    if row["family"] not in worst or value > worst[row["family"]][0]:
        worst[row["family"]] = (value, row)
print()
print("| family | worst row | max \\|e\\| (°) | mean e (°) | end e (°) |")
print("| --- | --- | ---: | ---: | ---: |")
for family, (value, row) in worst.items():
    cells = [f"{float(row[k]):.1f}" if row[k] else "failed" for k in keys]
    print("| " + " | ".join([family, row["world"]] + cells) + " |")
PY
