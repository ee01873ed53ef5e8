// libFuzzer target: the map loader (libs/memory load_map, an SQLite file); the seed corpus
// holds small valid maps for the mutations to start from.
#include "fuzz_support.hpp"
#include "omninav/memory/map_store.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace omninav;
  static const std::filesystem::path map = omninav::fuzz::scratch_dir() / "fuzz.vmem";
  std::error_code ignored;
  std::filesystem::remove(std::filesystem::path(map.string() + "-journal"), ignored);
  fuzz::write_file(map, fuzz::as_text(data, size));
  return fuzz::expect_clean([] { (void)memory::load_map(map); });
}
