// libFuzzer target: database_metadata.yaml of a BoB image database (libs/io, bob::read_metadata,
// a private header of io's). The metadata alone: through BobDatabaseReader, a `videoFile` key
// would have the fuzzer open whatever file it names as a video, which is OpenCV's videoio
// (and its leaks), not a parser of ours.
#include "bob_format.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace omninav;
  static const std::filesystem::path file = fuzz::scratch_dir() / io::kBobMetadataFile;
  fuzz::write_file(file, fuzz::as_text(data, size));
  return fuzz::expect_clean([] { (void)io::bob::read_metadata(file); });
}
