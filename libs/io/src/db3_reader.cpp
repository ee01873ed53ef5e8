// ROS 2 bags in rosbag2's SQLite storage (.db3, the default before Iron), read by us: Debian
// packages no rosbag2. Tables: topics(id, name, type, serialization_format, ...) and
// messages(id, topic_id, timestamp, data), the data CDR. Rows are read in insertion order (the
// recording's), so that a damaged file gives the messages stored before the damage.

#include <sqlite3.h>

#include <map>
#include <memory>

#include "bag_backend.hpp"
#include "cdr.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::io::detail {
namespace {

using Statement = std::unique_ptr<sqlite3_stmt, decltype(&sqlite3_finalize)>;

class Db3Bag : public BagBackend {
 public:
  explicit Db3Bag(const std::filesystem::path& file) : file_(file) {
    sqlite3* db = nullptr;
    const int code = sqlite3_open_v2(file.string().c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
    db_.reset(db);
    if (code != SQLITE_OK) fail("cannot open as SQLite");
    // SQLite refuses a file shorter than its header says (a recording cut short) unless the
    // schema is writable: this lets the rows before the cut be read (the connection stays
    // read-only).
    sqlite3_exec(db_.get(), "PRAGMA writable_schema = ON", nullptr, nullptr, nullptr);
    const Statement topics = prepare("SELECT id, name, type, serialization_format FROM topics");
    while (step(topics.get(), "reading its topics")) {
      Topic topic;
      topic.name = text(topics.get(), 1);
      topic.type = text(topics.get(), 2);
      topic.format = text(topics.get(), 3);
      topics_[sqlite3_column_int64(topics.get(), 0)] = topic;
    }
    // The counts up to any damage (reading the images reports it).
    const Statement messages = prepare("SELECT topic_id FROM messages ORDER BY id");
    while (sqlite3_step(messages.get()) == SQLITE_ROW) {
      ++counts_[sqlite3_column_int64(messages.get(), 0)];
    }
  }

  std::string kind() const override { return "ROS 2 SQLite bag"; }

  std::vector<BagTopic> topics() override {
    std::vector<BagTopic> result;
    for (const auto& [id, topic] : topics_) {
      const auto count = counts_.find(id);
      result.push_back({topic.name, topic.type, count == counts_.end() ? 0 : count->second});
    }
    return result;
  }

  std::vector<StampedPose> poses(const std::string& topic) override {
    const auto [id, found] = find(topic);
    std::vector<StampedPose> result;
    const Statement statement = prepare("SELECT data FROM messages WHERE topic_id = ? ORDER BY id");
    sqlite3_bind_int64(statement.get(), 1, id);
    try {
      while (sqlite3_step(statement.get()) == SQLITE_ROW) {
        result.push_back(
            decode_cdr_pose(found.type, blob(statement.get()), where(topic, result.size())));
      }
    } catch (const InputError&) {
      // The poses before the damage; reading the images reports it.
    }
    return result;
  }

  void start_images(const std::string& topic) override {
    const auto [id, found] = find(topic);
    topic_ = found;
    images_ = prepare("SELECT data FROM messages WHERE topic_id = ? ORDER BY id");
    sqlite3_bind_int64(images_.get(), 1, id);
    index_ = 0;
  }

  std::optional<BagImage> next_image() override {
    if (!step(images_.get(), "reading the images of " + printable_name(topic_.name))) {
      return std::nullopt;
    }
    return decode_cdr_image(topic_.type, blob(images_.get()), where(topic_.name, index_++));
  }

 private:
  struct Topic {
    std::string name;
    std::string type;
    std::string format;
  };

  [[noreturn]] void fail(const std::string& doing) const {
    throw InputError(file_.string() + ": " + doing +
                     " (SQLite: " + (db_ ? sqlite3_errmsg(db_.get()) : "out of memory") + ")");
  }
  Statement prepare(const std::string& sql) {
    sqlite3_stmt* statement = nullptr;
    if (sqlite3_prepare_v2(db_.get(), sql.c_str(), -1, &statement, nullptr) != SQLITE_OK) {
      fail("not a ROS 2 SQLite bag, or a damaged one");
    }
    return Statement(statement, &sqlite3_finalize);
  }
  bool step(sqlite3_stmt* statement, const std::string& doing) {
    const int code = sqlite3_step(statement);
    if (code == SQLITE_ROW) return true;
    if (code == SQLITE_DONE) return false;
    fail("damaged, " + doing);
  }
  static std::string text(sqlite3_stmt* statement, int column) {
    const unsigned char* value = sqlite3_column_text(statement, column);
    return value ? reinterpret_cast<const char*>(value) : "";
  }
  static std::vector<std::uint8_t> blob(sqlite3_stmt* statement) {
    const auto* data = static_cast<const std::uint8_t*>(sqlite3_column_blob(statement, 0));
    return std::vector<std::uint8_t>(data, data + sqlite3_column_bytes(statement, 0));
  }
  std::pair<std::int64_t, Topic> find(const std::string& name) const {
    for (const auto& [id, topic] : topics_) {
      if (topic.name != name) continue;
      if (topic.format != "cdr") {
        throw InputError(file_.string() + ": topic " + printable_name(name) +
                         " is serialised as '" + printable_name(topic.format) +
                         "'; omninav reads ROS 2's 'cdr'");
      }
      return {id, topic};
    }
    throw InputError(file_.string() + ": no topic " + printable_name(name));
  }
  std::string where(const std::string& topic, std::size_t index) const {
    return file_.string() + "#" + printable_name(topic) + " message " + std::to_string(index);
  }

  std::filesystem::path file_;
  std::unique_ptr<sqlite3, decltype(&sqlite3_close)> db_{nullptr, &sqlite3_close};
  std::map<std::int64_t, Topic> topics_;
  std::map<std::int64_t, std::size_t> counts_;
  Topic topic_;
  Statement images_{nullptr, &sqlite3_finalize};
  std::size_t index_ = 0;
};

}  // namespace

std::unique_ptr<BagBackend> open_db3(const std::filesystem::path& file) {
  return std::make_unique<Db3Bag>(file);
}

}  // namespace omninav::io::detail
