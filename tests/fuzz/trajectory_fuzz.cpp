// libFuzzer target: trajectory specs (libs/sim, `kind:key=value,...`) in the built-in room.
// Specs naming a file (csv:path=...) are left out: the file, not the spec, would be read, and
// the CSV readers have targets of their own.
#include "fuzz_support.hpp"
#include "omninav/core/log.hpp"
#include "omninav/sim/room.hpp"
#include "omninav/sim/trajectory.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace omninav;
  static const sim::World room = [] {
    set_log_level(LogLevel::kError);  // no warning about poses inside furniture, per input
    sim::RoomParams params;
    params.texture_px_per_m = 10.0;  // the textures are never looked at
    return sim::make_room(params);
  }();
  const std::string spec(fuzz::as_text(data, size));
  if (spec.find("path") != std::string::npos) return 0;
  return fuzz::expect_clean([&] { (void)sim::make_trajectory(spec, room); });
}
