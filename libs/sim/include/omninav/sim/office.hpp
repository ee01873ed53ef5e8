#pragma once
// An open-plan office laid out periodically: rows of identical desks (with a screen and a
// chair) at a regular pitch, and square columns at a regular pitch in the aisles, under a
// regular grid of ceiling lights. Places one desk pitch apart look nearly the same: the
// perceptual aliasing of Menegatti et al. 2004, §3.4. `clutter` puts a random object on a
// share of the desks, breaking the symmetry a little (0 = perfectly periodic).
// Desks and columns are obstacles. Seeded and deterministic.

#include "omninav/sim/world.hpp"

namespace omninav::sim {

struct OfficeParams {
  int rows = 3;  // rows of desks along x
  int desks_per_row = 6;
  double desk_pitch_m = 2.0;  // centre to centre along a row
  double row_pitch_m = 3.2;   // centre to centre across rows
  int column_every = 2;       // a column every this many desk pitches, in the aisles
  double height_m = 2.8;
  double clutter = 0.0;  // share of desks with a random object on them
  double texture_px_per_m = 100.0;
  int seed = 1;
};

// Reads an office's keys from worlds.yaml's `office:` section or from a spec (same keys).
template <typename Reader>
void read_office_keys(const Reader& reader, OfficeParams& params) {
  reader.read("rows", params.rows, 1, 8);
  reader.read("desks_per_row", params.desks_per_row, 2, 16);
  reader.read("desk_pitch_m", params.desk_pitch_m, 1.8, 4.0);
  reader.read("row_pitch_m", params.row_pitch_m, 2.6, 6.0);
  reader.read("column_every", params.column_every, 1, 8);
  reader.read("height_m", params.height_m, 2.4, 5.0);
  reader.read("clutter", params.clutter, 0.0, 1.0);
  reader.read("texture_px_per_m", params.texture_px_per_m, 10.0, 400.0);
  reader.read("seed", params.seed, 0, 1'000'000'000);
}

World make_office(const OfficeParams& params);

}  // namespace omninav::sim
