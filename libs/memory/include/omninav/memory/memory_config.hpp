#pragma once
// config/memory.yaml: the signature, exploration and localisation parameters in one file
// (docs/design.md, Conventions: Config). The file documents every key with its unit, range and
// source.

#include "omninav/compass/compass_config.hpp"
#include "omninav/memory/exploration.hpp"
#include "omninav/memory/localisation.hpp"
#include "omninav/memory/visual_memory.hpp"

namespace omninav {
class ConfigReader;
}

namespace omninav::memory {

struct MemoryConfig {
  MapParameters map;  // signature: components, colour; weights (Eq. 6)
  ExplorationParams exploration;
  LocalisationParams localisation;
};

// Reads sections signature (components, colour, weights), exploration and localisation, then
// rejects unknown keys. Throws ConfigError naming the file and key.
MemoryConfig load_memory_config(const ConfigReader& config);

// The visual compass that heading_source compass (or auto) uses: compass.yaml's compass and its
// input width.
void use_compass_config(const compass::CompassConfig& compass, ExplorationParams& exploration);

}  // namespace omninav::memory
