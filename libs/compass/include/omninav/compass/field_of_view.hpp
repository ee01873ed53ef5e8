#pragma once
// The field of view the distance function looks at (Labrosse 2006, §3.4.3): the whole
// panorama, or two bands of width f centred on the robot's front and back, where a forward or
// backward translation moves the image least (Fig. 10; f = 60°, Table 2).
//
// WHICH IMAGE THE MASK BELONGS TO. The paper: "When column-wise shifting the second image in
// Equation (2), the reduced field of view is also shifted to align it with the current
// estimation of where the front and back are in the second image." So the mask is a set of
// columns OF THE SECOND IMAGE (I_j, the current image in Algorithm 1), and it travels with that
// image when it is shifted: d(I_i, I_j, α) compares the front and back bands of I_j with the
// columns of I_i they land on after the shift. Written over the columns k of I_j:
//     d²(α) = Σ_k m(k) · Σ_rows,channels (I_j(k) − I_i(k + α))²
// (distance.hpp gives the shift convention). Pixels of I_j outside its bands never count, for
// any α; every column of I_i can count, depending on α.
//
// WHICH COLUMNS. Column c looks along azimuth π/2 − 2π·c/W (core/panorama.hpp), so the front is
// column 0.25·W and the back 0.75·W. A column belongs to a band when its centre looks within
// f/2 of the front or of the back, boundary included: |c − 0.25·W| ≤ f·W/720 (circularly), and
// the same about 0.75·W. At W = 360 and f = 60° that is columns 60..120 and 240..300 (61 each);
// at W = 1080, 180..360 and 720..900 (181 each). When W is a multiple of 4 the two bands are
// exactly W/2 apart, so shifting the mask by W/2 gives the same mask.

#include <cstdint>
#include <utility>
#include <vector>

namespace omninav::compass {

struct FieldOfViewParams {
  // true: the front and back bands of §3.4.3 (Table 2); false: the whole panorama (§3.2).
  bool front_back = true;
  // f, the width of each band, radians (60°, §3.4.3 and Table 2 of Labrosse 2006).
  double band_width_rad = 60.0 * 3.14159265358979323846 / 180.0;
};

// The columns of the second image that the distance compares.
class ColumnMask {
 public:
  // Every column.
  static ColumnMask whole(int width_px);
  // The front and back bands of total angular width band_width_rad each (see above). A band of
  // 180° or more covers everything and gives the whole mask.
  static ColumnMask front_back(int width_px, double band_width_rad);
  static ColumnMask from_params(int width_px, const FieldOfViewParams& params);

  int width_px() const { return width_px_; }
  bool selected(int column) const { return selected_[static_cast<std::size_t>(column)] != 0; }
  // The selected columns as ascending half-open runs [begin, end) within [0, W).
  const std::vector<std::pair<int, int>>& runs() const { return runs_; }
  int selected_count() const { return selected_count_; }
  bool is_whole() const { return selected_count_ == width_px_; }
  // A value that differs between masks of different columns (to key caches).
  std::uint64_t key() const { return key_; }

 private:
  ColumnMask(int width_px, std::vector<std::uint8_t> selected);

  int width_px_ = 0;
  std::vector<std::uint8_t> selected_;
  std::vector<std::pair<int, int>> runs_;
  int selected_count_ = 0;
  std::uint64_t key_ = 0;
};

}  // namespace omninav::compass
