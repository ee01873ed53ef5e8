#include "omninav/report/memory_figures.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "omninav/core/errors.hpp"

namespace omninav::report {
namespace {

// A map built in memory is not read through memory::load_map, which refuses absurd positions: the
// figures check them themselves, before any distance overflows or a loop over distances spins.
TEST(SignatureFigures, RefuseAnAbsurdTruthBeforeWritingAnything) {
  memory::VisualMemory memory;
  for (int i = 0; i < 8; ++i) {
    memory::Place place;
    place.signature = {45, 1, 15, 360, std::vector<float>(675, 1.f), std::vector<float>(675, 0.f)};
    place.source = "image_" + std::to_string(i) + ".png";
    place.frame_index = i;
    place.truth = CameraPose{0.3 * i, 1.0, 1.0, 0.0, 0.0, 0.0};
    if (i == 2) place.truth->x_m = 1e160;
    memory.add_place(std::move(place));
  }
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / "omninav_figures_absurd_truth";
  std::filesystem::remove_all(folder);
  try {
    write_signature_figures(memory, folder);
    FAIL() << "no InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("place 2 has a true position of (1e+160"),
              std::string::npos)
        << error.what();
  }
  EXPECT_FALSE(std::filesystem::exists(folder));
}

}  // namespace
}  // namespace omninav::report
