#!/usr/bin/env bash
# Makes the pictures of docs/worlds.md with `omninav render` only: for each world family a
# contact sheet of panoramas at a few places (for the field, at camera heights from 2 cm to
# 1.5 m) and its plan from above (floor, obstacles, regions, the places rendered).
# Writes docs/worlds/<family>_panoramas.png and <family>_plan.png. About a minute.
#
# Usage: scripts/world_pictures.sh [BUILD_DIR] [OUT_DIR]
set -euo pipefail

here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$here/build}"
out="${2:-$here/docs/worlds}"
omninav="$build/bin/omninav"
[ -x "$omninav" ] || { echo "no $omninav: build the omninav target first" >&2; exit 1; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"

# picture NAME WORLD TRAJECTORY [noplan]: renders panoramas of camera.yaml's size (360x45, what omninav
# works on), keeps the contact sheet and the plan.
picture() {
  "$omninav" -q render --world "$2" --trajectory "$3" \
    --out "$work/$1" --force
  cp "$work/$1/contact_sheet.png" "$out/$1_panoramas.png"
  [ "${4:-}" = noplan ] || cp "$work/$1/plan.png" "$out/$1_plan.png"
}

picture room "room" "grid:x0=1.5,y0=1.2,nx=2,ny=2,spacing_m=2.6"
picture room_plain "room:seed=3,size_x_m=9,boxes=12,walls=plain" \
  "grid:x0=1.5,y0=1.2,nx=2,ny=2,spacing_m=2.8" noplan
# Three rooms of the default house (rooms 1, 2 and 5 of its plan), in their free space.
printf 'x_m,y_m,heading_deg\n2.2,2.5,0\n6.2,3.3,0\n9.5,6.5,0\n' >"$work/rooms.csv"
picture house "house" "csv:path=$work/rooms.csv"
picture office "office" "grid:x0=3.5,y0=4.3,nx=3,ny=1,spacing_m=2.0"  # one desk pitch apart
# The field from one place at the heights insect-navigation studies use, then a few places.
printf 'x_m,y_m,heading_deg,z_m\n10,10,0,0.02\n10,10,0,0.2\n10,10,0,1.5\n' \
  >"$work/heights.csv"
picture field "field" "csv:path=$work/heights.csv"
picture field_hills "field:seed=4,horizon=hills,tussocks=12000,trees=2" \
  "grid:x0=4,y0=10,nx=3,ny=1,spacing_m=6,z_m=0.3" noplan
ls -l "$out"
