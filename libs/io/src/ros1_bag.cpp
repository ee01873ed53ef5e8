// ROS 1 bags through Debian's librosbag (rosbag_storage) and cv_bridge. Compiled as C++17: the
// generated ROS 1 message headers use std::allocator<void>::rebind, which C++20 removed.

#include <bzlib.h>
#include <cv_bridge/cv_bridge.h>
#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/exceptions.h>
#include <rosbag/view.h>
#include <roslz4/lz4s.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/image_encodings.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <string>
#include <vector>

#include "bag_backend.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/io/image_file.hpp"

namespace omninav::io::detail {
namespace {

template <typename Pose>
StampedPose stamped(const std_msgs::Header& header, const Pose& pose) {
  StampedPose result;
  result.stamp_s = header.stamp.toSec();
  result.x_m = pose.position.x;
  result.y_m = pose.position.y;
  result.z_m = pose.position.z;
  result.qx = pose.orientation.x;
  result.qy = pose.orientation.y;
  result.qz = pose.orientation.z;
  result.qw = pose.orientation.w;
  return result;
}

std::string reindex_advice(const std::filesystem::path& file) {
  return "`rosbag reindex " + file.filename().string() +
         "` (Debian's python3-rosbag) recovers the messages before the damage";
}

// librosbag allocates whatever length a record declares (a 4 GB header in a 40 KB file) and
// a chunk's declared uncompressed size: the records are walked first (format 2.0: a 13-byte
// magic, then records of header length, header, data length, data; header fields of length and
// "name=value"), every length checked against the file and every chunk's size against the
// largest a recorder writes. A file cut short (its index beyond its end) is left to librosbag,
// whose error says how to recover it.
constexpr std::uint64_t kMaxChunkBytes = std::uint64_t{256} << 20;  // as MCAP's (mcap_reader)

// A chunk's data as librosbag holds it after reading: the bytes themselves ("none"), or
// decompressed by the libraries librosbag uses (bzip2, roslz4) into at most the chunk's declared
// size. Nothing when they are not exactly that size (as a recorder writes them) or do not
// decompress; a compression librosbag does not know is left to librosbag's own error.
std::optional<std::string> chunk_records(const std::string& compression, std::string data,
                                         std::uint32_t declared_bytes) {
  std::string chunk(declared_bytes, '\0');
  unsigned int decompressed = declared_bytes;
  if (compression == "none") {
    chunk = std::move(data);
    decompressed = static_cast<unsigned int>(chunk.size());
  } else if (compression == "bz2") {
    if (BZ2_bzBuffToBuffDecompress(chunk.data(), &decompressed, data.data(),
                                   static_cast<unsigned int>(data.size()), 0, 0) != BZ_OK) {
      return std::nullopt;
    }
  } else if (compression == "lz4") {
    if (roslz4_buffToBuffDecompress(data.data(), static_cast<unsigned int>(data.size()),
                                    chunk.data(), &decompressed) != ROSLZ4_OK) {
      return std::nullopt;
    }
  } else {
    return std::string();
  }
  if (decompressed != declared_bytes) return std::nullopt;
  return chunk;
}

void check_record_lengths(const std::filesystem::path& file) {
  std::ifstream stream(file, std::ios::binary);
  std::error_code error;
  const std::uint64_t size = std::filesystem::file_size(file, error);
  char magic[13] = {};
  if (error || !stream.read(magic, sizeof magic) || std::string(magic, 13) != "#ROSBAG V2.0\n") {
    return;  // librosbag says what it is not
  }
  const auto u32 = [](const std::string& bytes, std::size_t at) {
    std::uint32_t value = 0;
    for (int i = 3; i >= 0; --i) value = value << 8 | static_cast<unsigned char>(bytes[at + i]);
    return value;
  };
  std::uint64_t at = sizeof magic;
  std::optional<std::uint64_t> index_at;           // the bag header's index_pos
  std::vector<std::uint32_t> chunk_record_starts;  // of the last chunk, in increasing order
  while (at < size) {
    const auto damaged = [&](const std::string& what) {
      // Cut short before its index: librosbag's own error (and the advice to reindex).
      if (index_at && *index_at > size) return;
      throw InputError(file.string() + ": damaged ROS 1 bag: the record at byte " +
                       std::to_string(at) + " " + what);
    };
    std::string length(4, '\0');
    if (size - at < 4 || !stream.read(length.data(), 4)) return damaged("is cut short");
    const std::uint32_t header_bytes = u32(length, 0);
    if (header_bytes > size - at - 4) {
      return damaged("declares a header of " + std::to_string(header_bytes) +
                     " bytes, beyond the end of the file");
    }
    std::string header(header_bytes, '\0');
    stream.read(header.data(), header_bytes);
    std::string op, compression;
    std::optional<std::uint64_t> field_u64;
    std::optional<std::uint32_t> chunk_size;
    for (std::size_t field = 0; field + 4 <= header.size();) {
      const std::uint32_t field_bytes = u32(header, field);
      if (field_bytes > header.size() - field - 4) return damaged("has a header field too long");
      const std::string text = header.substr(field + 4, field_bytes);
      const std::size_t equals = text.find('=');
      const std::string name = text.substr(0, equals);
      const std::string value = equals == std::string::npos ? "" : text.substr(equals + 1);
      if (name == "op" && value.size() == 1) op = value;
      if (name == "compression") compression = value;
      if (name == "size" && value.size() == 4) chunk_size = u32(value, 0);
      if (name == "index_pos" && value.size() == 8) {
        field_u64 = std::uint64_t{u32(value, 4)} << 32 | u32(value, 0);
      }
      field += 4 + field_bytes;
    }
    if (op == "\x03" && field_u64) index_at = field_u64;
    if (op == "\x05" && chunk_size && *chunk_size > kMaxChunkBytes) {
      return damaged("is a chunk of " + std::to_string(*chunk_size) +
                     " bytes uncompressed, more than " + std::to_string(kMaxChunkBytes) +
                     " (not a recording's chunk)");
    }
    at += 4 + header_bytes;
    if (size - at < 4 || !stream.read(length.data(), 4)) return damaged("is cut short");
    const std::uint32_t data_bytes = u32(length, 0);
    if (data_bytes > size - at - 4) {
      return damaged("declares " + std::to_string(data_bytes) +
                     " bytes of data, beyond the end of the file");
    }
    if (op == "\x05" || op == "\x04") {
      std::string data(data_bytes, '\0');
      stream.seekg(static_cast<std::streamoff>(at + 4));
      stream.read(data.data(), data_bytes);
      if (op == "\x04") {
        // A chunk's index, after it: librosbag reads each message at the offset an entry gives
        // (format 2.0, version 1: time, 8 bytes, then offset, 4), which must be where a record
        // of that chunk starts.
        for (std::size_t entry = 0; entry + 12 <= data.size(); entry += 12) {
          const std::uint32_t offset = u32(data, entry + 8);
          if (!std::binary_search(chunk_record_starts.begin(), chunk_record_starts.end(), offset)) {
            return damaged("is an index naming byte " + std::to_string(offset) +
                           " of its chunk, where no record starts");
          }
        }
      } else {
        // A chunk's records (messages, connections) are read from memory by librosbag without
        // bounds, in a buffer of the chunk's declared size: the chunk is decompressed here as
        // librosbag decompresses it, and its records must fill exactly that size.
        const std::uint32_t declared = chunk_size.value_or(0);
        const std::optional<std::string> chunk =
            chunk_records(compression, std::move(data), declared);
        if (!chunk) {
          return damaged(compression == "none"
                             ? "is a chunk of " + std::to_string(data_bytes) +
                                   " bytes that declares " + std::to_string(declared)
                             : "is a " + printable_name(compression) +
                                   " chunk that does not decompress to the " +
                                   std::to_string(declared) + " bytes it declares");
        }
        chunk_record_starts.clear();
        for (std::size_t inner = 0; inner < chunk->size();) {
          chunk_record_starts.push_back(static_cast<std::uint32_t>(inner));
          for (int part = 0; part < 2; ++part) {  // header, then data
            if (chunk->size() - inner < 4 || u32(*chunk, inner) > chunk->size() - inner - 4) {
              return damaged("is a chunk whose record at its byte " + std::to_string(inner) +
                             " runs past its end");
            }
            inner += 4 + u32(*chunk, inner);
          }
        }
      }
    }
    at += 4 + data_bytes;
    stream.seekg(static_cast<std::streamoff>(at));
  }
}

class Ros1Bag : public BagBackend {
 public:
  explicit Ros1Bag(const std::filesystem::path& file) : file_(file) {
    check_record_lengths(file);
    try {
      bag_.open(file.string(), rosbag::bagmode::Read);
    } catch (const rosbag::BagUnindexedException&) {
      throw InputError(file.string() + ": the ROS 1 bag has no index (a recording cut short); " +
                       reindex_advice(file));
    } catch (const rosbag::BagIOException& error) {
      // The index is at the end: a file cut short loses it, and librosbag reads nothing.
      throw InputError(file.string() + ": the ROS 1 bag ends before its index (" + error.what() +
                       "): a truncated file; " + reindex_advice(file));
    } catch (const std::exception& error) {
      throw InputError(file.string() + ": cannot read as a ROS 1 bag (" + error.what() + ")");
    }
  }

  std::string kind() const override { return "ROS 1 bag"; }

  std::vector<BagTopic> topics() override {
    std::map<std::string, BagTopic> by_name;
    rosbag::View view(bag_);
    for (const rosbag::ConnectionInfo* connection : view.getConnections()) {
      BagTopic& topic = by_name[connection->topic];
      topic.name = connection->topic;
      topic.type = connection->datatype;
    }
    for (auto& [name, topic] : by_name) {
      topic.count = rosbag::View(bag_, rosbag::TopicQuery(name)).size();
    }
    std::vector<BagTopic> result;
    for (auto& entry : by_name) result.push_back(entry.second);
    return result;
  }

  std::vector<StampedPose> poses(const std::string& topic) override {
    std::vector<StampedPose> result;
    try {
      for (const rosbag::MessageInstance& message : rosbag::View(bag_, rosbag::TopicQuery(topic))) {
        if (const auto odometry = message.instantiate<nav_msgs::Odometry>()) {
          result.push_back(stamped(odometry->header, odometry->pose.pose));
        } else if (const auto pose = message.instantiate<geometry_msgs::PoseStamped>()) {
          result.push_back(stamped(pose->header, pose->pose));
        }
      }
    } catch (const std::exception&) {
      // The poses before the damage; reading the images reports it.
    }
    return result;
  }

  void start_images(const std::string& topic) override {
    topic_ = topic;
    view_ = std::make_unique<rosbag::View>(bag_, rosbag::TopicQuery(topic));
    at_ = view_->begin();
    index_ = 0;
  }

  std::optional<BagImage> next_image() override {
    const std::string where =
        file_.string() + "#" + printable_name(topic_) + " message " + std::to_string(index_);
    try {
      if (at_ == view_->end()) return std::nullopt;
      const rosbag::MessageInstance& message = *at_;
      BagImage result;
      if (const auto image = message.instantiate<sensor_msgs::Image>()) {
        result.stamp_s = image->header.stamp.toSec();
        RawImage raw;
        raw.height = image->height;
        raw.width = image->width;
        raw.encoding = image->encoding;
        raw.is_bigendian = image->is_bigendian != 0;
        raw.step = image->step;
        raw.data = image->data;
        result.image = decode_raw_image(std::move(raw), where);
      } else if (const auto compressed = message.instantiate<sensor_msgs::CompressedImage>()) {
        result.stamp_s = compressed->header.stamp.toSec();
        result.image = decode_compressed_image(compressed->data, compressed->format, where);
      } else {
        throw InputError(where + ": a " + message.getDataType() + ", not an image");
      }
      ++at_;
      ++index_;
      return result;
    } catch (const InputError&) {
      throw;
    } catch (const std::exception& error) {
      throw InputError(where + ": cannot read (" + error.what() + ")");
    }
  }

 private:
  std::filesystem::path file_;
  rosbag::Bag bag_;
  std::string topic_;
  std::unique_ptr<rosbag::View> view_;
  rosbag::View::iterator at_;
  std::size_t index_ = 0;
};

}  // namespace

std::unique_ptr<BagBackend> open_ros1_bag(const std::filesystem::path& file) {
  return std::make_unique<Ros1Bag>(file);
}

}  // namespace omninav::io::detail

namespace omninav::io {

cv::Mat decode_raw_image(RawImage image, const std::string& where) {
  namespace encodings = sensor_msgs::image_encodings;
  if (image.width == 0 || image.height == 0) throw InputError(where + ": an empty image");
  check_image_pixels(cv::Size(static_cast<int>(std::min<std::uint32_t>(image.width, 1u << 30)),
                              static_cast<int>(std::min<std::uint32_t>(image.height, 1u << 30))),
                     where);
  if (static_cast<std::uint64_t>(image.step) * image.height > image.data.size()) {
    throw InputError(where + ": " + std::to_string(image.data.size()) + " bytes of data for " +
                     std::to_string(image.height) + " rows of " + std::to_string(image.step) +
                     " bytes");
  }
  std::uint64_t row_bytes = 0;
  try {
    row_bytes = static_cast<std::uint64_t>(image.width) * encodings::numChannels(image.encoding) *
                (encodings::bitDepth(image.encoding) / 8);
  } catch (const std::exception&) {
    throw InputError(where + ": unknown image encoding '" + image.encoding + "'");
  }
  if (row_bytes == 0 || image.step < row_bytes) {
    throw InputError(where + ": rows of " + std::to_string(image.step) + " bytes (step) for " +
                     std::to_string(image.width) + " pixels of '" + image.encoding + "'");
  }
  sensor_msgs::Image message;
  message.height = image.height;
  message.width = image.width;
  message.encoding = image.encoding;
  message.is_bigendian = image.is_bigendian ? 1 : 0;
  message.step = image.step;
  message.data = std::move(image.data);
  try {
    const bool grey = !encodings::isBayer(image.encoding) && !encodings::isColor(image.encoding) &&
                      encodings::numChannels(image.encoding) == 1;
    return cv_bridge::toCvCopy(message, grey ? encodings::MONO8 : encodings::BGR8)->image;
  } catch (const std::exception& error) {
    throw InputError(where + ": image encoding '" + image.encoding + "' (" + error.what() + ")");
  }
}

cv::Mat decode_compressed_image(const std::vector<std::uint8_t>& data, const std::string& format,
                                const std::string& where) {
  if (format.find("compressedDepth") != std::string::npos) {
    throw InputError(where + ": a compressed depth image ('" + printable_name(format) +
                     "'), not a picture");
  }
  cv::Mat image = decode_image(data, cv::IMREAD_ANYCOLOR, where);
  if (image.empty()) {
    throw InputError(where + ": cannot decode the compressed image ('" + printable_name(format) +
                     "')");
  }
  return image;
}

}  // namespace omninav::io
