// ROS 2 bags in MCAP (https://mcap.dev/spec), read by us: Debian packages no MCAP library (nor
// rosbag2). The file is read front to back, record by record, without its summary section, so
// that a file cut short (a recording killed mid-write) still gives the messages before the cut.
// Chunks compressed with zstd or lz4 are decompressed with Debian's libzstd and liblz4, and
// checked against their CRC-32 (the spec's "CRC-32 (IEEE 802.3)", which is zlib's crc32).

#include <lz4frame.h>
#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <memory>

#include "bag_backend.hpp"
#include "cdr.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::io::detail {
namespace {

constexpr char kMagic[] = "\x89MCAP0\r\n";
constexpr std::size_t kMagicBytes = 8;
// rosbag2 writes chunks of 768 kB by default; a larger limit than any recorder's, so that a
// damaged size cannot make the reader allocate without bound.
constexpr std::uint64_t kMaxChunkBytes = std::uint64_t{256} << 20;

enum Opcode : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kDataEnd = 0x0F,
};

// Little-endian fields of one record's content.
class Fields {
 public:
  Fields(const std::uint8_t* data, std::size_t size, const std::string& where)
      : data_(data), size_(size), where_(where) {}

  std::uint16_t u16() { return static_cast<std::uint16_t>(little(2)); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(little(4)); }
  std::uint64_t u64() { return little(8); }
  std::string string() {
    const std::uint32_t length = u32();
    need(length);
    std::string text(reinterpret_cast<const char*>(data_ + offset_), length);
    offset_ += length;
    return text;
  }
  void skip(std::uint64_t count) {
    need(count);
    offset_ += count;
  }
  const std::uint8_t* here() const { return data_ + offset_; }
  std::size_t left() const { return size_ - offset_; }

 private:
  void need(std::uint64_t count) const {
    if (count > size_ - offset_) throw InputError(where_ + ": a record shorter than its fields");
  }
  std::uint64_t little(int bytes) {
    need(static_cast<std::uint64_t>(bytes));
    std::uint64_t value = 0;
    for (int i = bytes - 1; i >= 0; --i) value = (value << 8) | data_[offset_ + i];
    offset_ += static_cast<std::size_t>(bytes);
    return value;
  }

  const std::uint8_t* data_;
  std::size_t size_;
  const std::string& where_;
  std::size_t offset_ = 0;
};

// CRC-32 of `bytes`, fed to zlib in pieces its uInt length can hold.
std::uint32_t crc32_of(const std::vector<std::uint8_t>& bytes) {
  uLong crc = ::crc32(0L, Z_NULL, 0);
  constexpr std::size_t kPiece = std::size_t{1} << 30;
  for (std::size_t at = 0; at < bytes.size(); at += kPiece) {
    crc = ::crc32(crc, bytes.data() + at, static_cast<uInt>(std::min(kPiece, bytes.size() - at)));
  }
  return static_cast<std::uint32_t>(crc);
}

struct Channel {
  std::string topic;
  std::string type;  // the schema's name, "sensor_msgs/msg/Image"
  std::string encoding;
};

struct Message {
  std::uint16_t channel = 0;
  std::vector<std::uint8_t> data;
};

// The messages of an MCAP file in file order, with the channels met so far.
class Cursor {
 public:
  explicit Cursor(const std::filesystem::path& file)
      : file_(file), stream_(file, std::ios::binary) {
    char magic[kMagicBytes] = {};
    if (!stream_.read(magic, kMagicBytes) || std::string(magic, kMagicBytes) != kMagic) {
      throw InputError(file.string() + ": not an MCAP file (no MCAP magic at its start)");
    }
    position_ = kMagicBytes;
    std::error_code error;
    file_size_ = std::filesystem::file_size(file, error);
  }

  // The next message, or false at the end of the data. Throws InputError at damage.
  bool next(Message& message) {
    while (true) {
      if (chunk_offset_ < chunk_.size()) {
        if (read_record(chunk_, chunk_offset_, message,
                        "chunk at byte " + std::to_string(chunk_position_))) {
          return true;
        }
        continue;
      }
      if (ended_) return false;
      std::uint8_t head[9];
      stream_.read(reinterpret_cast<char*>(head), 9);
      if (stream_.gcount() == 0) {
        throw InputError(file_.string() + ": ends at byte " + std::to_string(position_) +
                         " without MCAP's footer (a truncated file)");
      }
      if (stream_.gcount() < 9) throw truncated();
      std::uint64_t length = 0;
      for (int i = 8; i >= 1; --i) length = (length << 8) | head[i];
      const std::uint8_t opcode = head[0];
      if (opcode == kDataEnd || opcode == kFooter) {
        ended_ = true;
        return false;
      }
      if (length > file_size_ - std::min(file_size_, position_ + 9)) throw truncated();
      std::vector<std::uint8_t> content(length);
      stream_.read(reinterpret_cast<char*>(content.data()), static_cast<std::streamsize>(length));
      if (static_cast<std::uint64_t>(stream_.gcount()) != length) throw truncated();
      const std::uint64_t record_position = position_;
      position_ += 9 + length;
      if (opcode == kChunk) {
        chunk_ = decompress(content, record_position);
        chunk_offset_ = 0;
        chunk_position_ = record_position;
        continue;
      }
      std::vector<std::uint8_t> record(9 + length);
      std::copy(head, head + 9, record.begin());
      std::copy(content.begin(), content.end(), record.begin() + 9);
      std::size_t offset = 0;
      if (read_record(record, offset, message, "byte " + std::to_string(record_position))) {
        return true;
      }
    }
  }

  const std::map<std::uint16_t, Channel>& channels() const { return channels_; }
  const std::filesystem::path& file() const { return file_; }

 private:
  InputError truncated() const {
    return InputError(file_.string() + ": cut short in the record at byte " +
                      std::to_string(position_) + " (a truncated file)");
  }

  // Reads the record at `offset` of `records` (opcode, length, content); true for a message.
  bool read_record(const std::vector<std::uint8_t>& records, std::size_t& offset, Message& message,
                   const std::string& at) {
    const std::string where = file_.string() + ": the record in the " + at;
    if (records.size() - offset < 9) throw InputError(where + " is cut short");
    std::uint64_t length = 0;
    for (int i = 8; i >= 1; --i) length = (length << 8) | records[offset + i];
    const std::uint8_t opcode = records[offset];
    if (length > records.size() - offset - 9) throw InputError(where + " is cut short");
    Fields fields(records.data() + offset + 9, length, where);
    offset += 9 + length;
    if (opcode == kSchema) {
      const std::uint16_t id = fields.u16();
      schemas_[id] = fields.string();
    } else if (opcode == kChannel) {
      const std::uint16_t id = fields.u16();
      const std::uint16_t schema = fields.u16();
      Channel channel;
      channel.topic = fields.string();
      channel.encoding = fields.string();
      const auto found = schemas_.find(schema);
      channel.type = found == schemas_.end() ? "(no schema)" : found->second;
      channels_[id] = channel;
    } else if (opcode == kMessage) {
      message.channel = fields.u16();
      fields.u32();  // sequence
      fields.u64();  // log time
      fields.u64();  // publish time
      message.data.assign(fields.here(), fields.here() + fields.left());
      if (!channels_.count(message.channel)) {
        throw InputError(where + ": a message on channel " + std::to_string(message.channel) +
                         ", which no channel record defined before it");
      }
      return true;
    }
    return false;
  }

  std::vector<std::uint8_t> decompress(const std::vector<std::uint8_t>& content,
                                       std::uint64_t record_position) {
    const std::string where =
        file_.string() + ": the chunk at byte " + std::to_string(record_position);
    Fields fields(content.data(), content.size(), where);
    fields.u64();  // message start time
    fields.u64();  // message end time
    const std::uint64_t size = fields.u64();
    const std::uint32_t crc = fields.u32();  // of the uncompressed records; 0: not computed
    const std::string compression = fields.string();
    const std::uint64_t compressed_size = fields.u64();
    if (compressed_size > fields.left()) throw InputError(where + " is cut short");
    if (size > kMaxChunkBytes) {
      throw InputError(where + ": " + std::to_string(size) + " bytes uncompressed, more than " +
                       std::to_string(kMaxChunkBytes) + " (not a recording's chunk)");
    }
    const std::uint8_t* compressed = fields.here();
    std::vector<std::uint8_t> records(size);
    if (compression.empty()) {
      if (compressed_size != size) throw InputError(where + ": sizes disagree");
      std::copy(compressed, compressed + size, records.begin());
    } else if (compression == "zstd") {
      const std::size_t made = ZSTD_decompress(records.data(), size, compressed, compressed_size);
      if (ZSTD_isError(made) || made != size) {
        throw InputError(where + ": cannot decompress (zstd: " +
                         (ZSTD_isError(made) ? ZSTD_getErrorName(made) : "wrong size") + ")");
      }
    } else if (compression == "lz4") {
      LZ4F_dctx* context = nullptr;
      if (LZ4F_isError(LZ4F_createDecompressionContext(&context, LZ4F_VERSION))) {
        throw InputError(where + ": cannot start lz4");
      }
      const std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> owner(
          context, &LZ4F_freeDecompressionContext);
      std::size_t made = 0;
      std::size_t used = 0;
      while (used < compressed_size) {
        std::size_t out = size - made;
        std::size_t in = compressed_size - used;
        const std::size_t status =
            LZ4F_decompress(context, records.data() + made, &out, compressed + used, &in, nullptr);
        if (LZ4F_isError(status)) {
          throw InputError(where + ": cannot decompress (lz4: " + LZ4F_getErrorName(status) + ")");
        }
        made += out;
        used += in;
        if (status == 0) break;
        if (in == 0 && out == 0) throw InputError(where + ": cannot decompress (lz4 stalled)");
      }
      if (made != size) throw InputError(where + ": cannot decompress (lz4: wrong size)");
    } else {
      throw InputError(where + ": compressed with '" + printable_name(compression) +
                       "' (omninav reads zstd, lz4 and uncompressed chunks)");
    }
    if (crc != 0 && crc32_of(records) != crc) {
      throw InputError(where + " is damaged (its records do not match the chunk's CRC-32)");
    }
    return records;
  }

  std::filesystem::path file_;
  std::ifstream stream_;
  std::uint64_t position_ = 0;
  std::uint64_t file_size_ = 0;
  bool ended_ = false;
  std::vector<std::uint8_t> chunk_;
  std::size_t chunk_offset_ = 0;
  std::uint64_t chunk_position_ = 0;
  std::map<std::uint16_t, std::string> schemas_;
  std::map<std::uint16_t, Channel> channels_;
};

class McapBag : public BagBackend {
 public:
  explicit McapBag(const std::filesystem::path& file) : file_(file) {
    // A first pass: the topics, their counts, and the poses, up to any damage.
    Cursor cursor(file);
    Message message;
    try {
      while (cursor.next(message)) ++counts_[message.channel];
    } catch (const InputError& error) {
      // next_image reports it when the images reach it; damage() when it hides the topics.
      damage_ = error.what();
    }
    channels_ = cursor.channels();
  }

  std::string kind() const override { return "MCAP"; }
  std::optional<std::string> damage() const override { return damage_; }

  std::vector<BagTopic> topics() override {
    std::map<std::string, BagTopic> by_name;
    for (const auto& [id, channel] : channels_) {
      BagTopic& topic = by_name[channel.topic];
      topic.name = channel.topic;
      topic.type = channel.type;
      const auto count = counts_.find(id);
      if (count != counts_.end()) topic.count += count->second;
    }
    std::vector<BagTopic> result;
    for (auto& entry : by_name) result.push_back(entry.second);
    return result;
  }

  std::vector<StampedPose> poses(const std::string& topic) override {
    std::vector<StampedPose> result;
    Cursor cursor(file_);
    Message message;
    std::size_t index = 0;
    try {
      while (cursor.next(message)) {
        const Channel& channel = cursor.channels().at(message.channel);
        if (channel.topic != topic) continue;
        check_cdr(channel);
        result.push_back(decode_cdr_pose(channel.type, message.data, where(topic, index++)));
      }
    } catch (const InputError&) {
      // The poses before the damage; reading the images reports it.
    }
    return result;
  }

  void start_images(const std::string& topic) override {
    topic_ = topic;
    cursor_ = std::make_unique<Cursor>(file_);
    index_ = 0;
  }

  std::optional<BagImage> next_image() override {
    Message message;
    while (cursor_->next(message)) {
      const Channel& channel = cursor_->channels().at(message.channel);
      if (channel.topic != topic_) continue;
      check_cdr(channel);
      return decode_cdr_image(channel.type, message.data, where(topic_, index_++));
    }
    return std::nullopt;
  }

 private:
  std::string where(const std::string& topic, std::size_t index) const {
    return file_.string() + "#" + printable_name(topic) + " message " + std::to_string(index);
  }
  void check_cdr(const Channel& channel) const {
    if (channel.encoding != "cdr") {
      throw InputError(file_.string() + ": topic " + printable_name(channel.topic) +
                       " is encoded as '" + printable_name(channel.encoding) +
                       "'; omninav reads ROS 2's 'cdr'");
    }
  }

  std::filesystem::path file_;
  std::map<std::uint16_t, Channel> channels_;
  std::map<std::uint16_t, std::size_t> counts_;
  std::optional<std::string> damage_;
  std::string topic_;
  std::unique_ptr<Cursor> cursor_;
  std::size_t index_ = 0;
};

}  // namespace

std::unique_ptr<BagBackend> open_mcap(const std::filesystem::path& file) {
  return std::make_unique<McapBag>(file);
}

}  // namespace omninav::io::detail
