#pragma once
// Reading config/compass.yaml into the compass's parameters. Every key is optional (absent keys
// keep the defaults of the Params structs, which are those of Table 2 of
// Labrosse 2006); unknown keys are the caller's ConfigReader::require_all_known().

#include <optional>

#include "omninav/compass/min_warping.hpp"
#include "omninav/compass/visual_compass.hpp"

namespace omninav {
class ConfigReader;
}

namespace omninav::compass {

struct CompassConfig {
  CompassParams compass;
  // Resample every input panorama to this many columns first (resample.hpp); absent: use the
  // input's own width. Table 2 used 360 (one pixel per degree).
  std::optional<int> width_px;
  // Min-warping (min_warping.hpp): home vectors and the joint turn-and-travel estimate.
  MinWarpingParams min_warping;
};

// Reads the sections distance, minimiser, phase, subpixel, sampling, confidence, uncertainty,
// min_warping and input, then checks the values (CompassParams::check, MinWarpingParams::check).
// Throws ConfigError naming the file, the key and the valid range or choices, or the
// combination that cannot work (the fft minimiser with the l1 metric).
void load_compass_config(const ConfigReader& config, CompassConfig& out);

}  // namespace omninav::compass
