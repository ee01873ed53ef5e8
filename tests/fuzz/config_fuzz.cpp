// libFuzzer target: a YAML configuration file (libs/core ConfigReader, through yaml-cpp), read
// by the loader of memory.yaml, which also checks that every key is known.
#include "fuzz_support.hpp"
#include "omninav/core/config.hpp"
#include "omninav/memory/memory_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace omninav;
  const std::string yaml(fuzz::as_text(data, size));
  return fuzz::expect_clean(
      [&] { (void)memory::load_memory_config(ConfigReader::from_string(yaml, "memory.yaml")); });
}
