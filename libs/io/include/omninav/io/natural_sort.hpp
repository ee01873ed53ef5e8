#pragma once
// Natural order of file names, so that a folder of frames reads img2 before img10 (docs/design.md,
// Data formats: a folder of images, natural sort).

#include <filesystem>
#include <string_view>
#include <vector>

namespace omninav::io {

// True when `a` sorts before `b`: runs of digits compare by numeric value ("img2" < "img10"),
// other characters case-insensitively. Names that differ only in case or in leading zeros fall
// back to plain byte order, so the order is total and the same on every machine.
bool natural_less(std::string_view a, std::string_view b);

// Sorts paths by their file name in natural order.
void natural_sort(std::vector<std::filesystem::path>& files);

}  // namespace omninav::io
