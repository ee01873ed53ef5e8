#include "cdr.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>

#include "omninav/core/errors.hpp"

namespace omninav::io::detail {
namespace {

class CdrReader {
 public:
  CdrReader(const std::vector<std::uint8_t>& data, const std::string& where)
      : data_(data), where_(where) {
    if (data.size() < 4) fail("shorter than a CDR header");
    // Encapsulation kinds: 0 CDR_BE, 1 CDR_LE (and 2, 3: PL_CDR, which ROS 2 does not use).
    if (data[0] != 0 || data[1] > 1)
      fail("not plain CDR (encapsulation " + std::to_string(data[0] * 256 + data[1]) + ")");
    little_endian_ = data[1] == 1;
    offset_ = 4;
  }

  std::uint8_t u8() { return bytes_of<std::uint8_t>(); }
  std::uint32_t u32() { return bytes_of<std::uint32_t>(); }
  std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
  double f64() { return std::bit_cast<double>(bytes_of<std::uint64_t>()); }

  std::string string() {
    const std::uint32_t length = u32();  // with the terminating NUL
    need(length);
    std::string text(reinterpret_cast<const char*>(data_.data() + offset_), length);
    offset_ += length;
    if (!text.empty() && text.back() == '\0') text.pop_back();
    return text;
  }

  std::vector<std::uint8_t> bytes() {
    const std::uint32_t length = u32();
    need(length);
    std::vector<std::uint8_t> result(data_.begin() + static_cast<std::ptrdiff_t>(offset_),
                                     data_.begin() + static_cast<std::ptrdiff_t>(offset_ + length));
    offset_ += length;
    return result;
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(where_ + ": bad CDR message (" + what + ")");
  }

 private:
  void need(std::size_t count) const {
    if (count > data_.size() - offset_) {
      fail("ends at byte " + std::to_string(data_.size()) + ", wants " +
           std::to_string(offset_ + count));
    }
  }

  template <typename T>
  T bytes_of() {
    const std::size_t alignment = sizeof(T);
    offset_ = 4 + (offset_ - 4 + alignment - 1) / alignment * alignment;
    need(sizeof(T));
    T value;
    std::memcpy(&value, data_.data() + offset_, sizeof(T));
    offset_ += sizeof(T);
    if (little_endian_ != (std::endian::native == std::endian::little)) {
      value = std::bit_cast<T>(reversed(std::bit_cast<std::array<std::uint8_t, sizeof(T)>>(value)));
    }
    return value;
  }

  template <std::size_t N>
  static std::array<std::uint8_t, N> reversed(std::array<std::uint8_t, N> bytes) {
    std::reverse(bytes.begin(), bytes.end());
    return bytes;
  }

  const std::vector<std::uint8_t>& data_;
  const std::string& where_;
  bool little_endian_ = true;
  std::size_t offset_ = 0;
};

// std_msgs/msg/Header: builtin_interfaces/msg/Time stamp (int32 sec, uint32 nanosec), string
// frame_id. Returns the stamp in seconds.
double read_header(CdrReader& reader) {
  const std::int32_t sec = reader.i32();
  const std::uint32_t nanosec = reader.u32();
  reader.string();  // frame_id
  return sec + nanosec * 1e-9;
}

// geometry_msgs/msg/Pose: Point position (x, y, z), Quaternion orientation (x, y, z, w).
void read_pose(CdrReader& reader, StampedPose& pose) {
  pose.x_m = reader.f64();
  pose.y_m = reader.f64();
  pose.z_m = reader.f64();
  pose.qx = reader.f64();
  pose.qy = reader.f64();
  pose.qz = reader.f64();
  pose.qw = reader.f64();
}

}  // namespace

BagImage decode_cdr_image(const std::string& type, const std::vector<std::uint8_t>& data,
                          const std::string& where) {
  CdrReader reader(data, where);
  BagImage result;
  result.stamp_s = read_header(reader);
  if (is_image_compressed_type(type)) {
    const std::string format = reader.string();
    result.image = decode_compressed_image(reader.bytes(), format, where);
    return result;
  }
  RawImage image;
  image.height = reader.u32();
  image.width = reader.u32();
  image.encoding = reader.string();
  image.is_bigendian = reader.u8() != 0;
  image.step = reader.u32();
  image.data = reader.bytes();
  result.image = decode_raw_image(std::move(image), where);
  return result;
}

StampedPose decode_cdr_pose(const std::string& type, const std::vector<std::uint8_t>& data,
                            const std::string& where) {
  CdrReader reader(data, where);
  StampedPose pose;
  pose.stamp_s = read_header(reader);
  // nav_msgs/msg/Odometry: header, string child_frame_id, PoseWithCovariance (pose, then 36
  // covariances), TwistWithCovariance; geometry_msgs/msg/PoseStamped: header, pose.
  if (is_odometry_type(type)) reader.string();
  read_pose(reader, pose);
  return pose;
}

}  // namespace omninav::io::detail
