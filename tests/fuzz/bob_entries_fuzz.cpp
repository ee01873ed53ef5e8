// libFuzzer target: database_entries.csv of a BoB image database (libs/io), read whole, beside
// a fixed metadata file and one small image that its rows may name (0.png).
#include "fuzz_support.hpp"
#include "omninav/io/bob_database.hpp"
#include "omninav/io/sequence.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace omninav;
  static const std::filesystem::path folder = [] {
    const std::filesystem::path dir = fuzz::folder_with_image("bob_entries");
    fuzz::write_file(dir / io::kBobMetadataFile,
                     "metadata:\n  type: route\n  camera: {name: fuzz, resolution: [8, 4]}\n");
    return dir;
  }();
  fuzz::write_file(folder / io::kBobEntriesFile, fuzz::as_text(data, size));
  return fuzz::expect_clean([] {
    io::BobDatabaseReader reader(folder);
    (void)reader.describe();
    io::read_all(reader);
  });
}
