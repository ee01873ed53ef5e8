// libFuzzer target: database_metadata.yaml of a BoB image database (libs/io), which OpenCV's
// YAML parser reads, beside a fixed database_entries.csv of one row and its small image.
#include "fuzz_support.hpp"
#include "omninav/io/bob_database.hpp"
#include "omninav/io/sequence.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace omninav;
  static const std::filesystem::path folder = [] {
    const std::filesystem::path dir = fuzz::folder_with_image("bob_metadata");
    fuzz::write_file(dir / io::kBobEntriesFile,
                     "X [mm],Y [mm],Z [mm],Heading [degrees],Filename\n"
                     "10,20,0,90,0.png\n");
    return dir;
  }();
  fuzz::write_file(folder / io::kBobMetadataFile, fuzz::as_text(data, size));
  return fuzz::expect_clean([] { (void)io::read_all(*io::open_sequence(folder)); });
}
