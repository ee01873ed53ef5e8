#include "omninav/memory/memory_config.hpp"

#include "omninav/core/config.hpp"
#include "omninav/signature/dissimilarity.hpp"

namespace omninav::memory {

MemoryConfig load_memory_config(const ConfigReader& config) {
  MemoryConfig out;
  const ConfigReader signature_section = config.section("signature");
  signature::load_signature_params(signature_section, out.map.signature);
  std::string weights = signature::to_string(out.map.weights);
  signature_section.read("weights", weights, {});
  out.map.weights = signature::parse_component_weights(
      weights, config.source_name() + ": key 'signature.weights'");
  load_exploration_params(config.section("exploration"), out.exploration);
  load_localisation_params(config.section("localisation"), out.localisation);
  config.require_all_known();
  return out;
}

void use_compass_config(const compass::CompassConfig& compass, ExplorationParams& exploration) {
  exploration.compass = compass.compass;
  exploration.compass_width_px = compass.width_px;
}

}  // namespace omninav::memory
