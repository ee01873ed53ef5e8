// libFuzzer target: the CSV sequence (libs/io, `file, x_m, y_m, heading_deg` rows), read whole,
// beside one small image its rows may name (0.png).
#include "fuzz_support.hpp"
#include "omninav/io/csv_sequence.hpp"
#include "omninav/io/sequence.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace omninav;
  static const std::filesystem::path csv = fuzz::folder_with_image("csv") / "poses.csv";
  fuzz::write_file(csv, fuzz::as_text(data, size));
  return fuzz::expect_clean([] {
    io::CsvSequence sequence(csv);
    (void)sequence.describe();
    io::read_all(sequence);
  });
}
