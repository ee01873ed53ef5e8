#include "bob_format.hpp"

#include <cmath>
#include <cstring>
#include <fstream>
#include <opencv2/core/persistence.hpp>
#include <sstream>

#include "omninav/core/errors.hpp"

namespace omninav::io::bob {
namespace {

class MetadataParser {
 public:
  MetadataParser(const std::filesystem::path& file, cv::FileNode metadata)
      : file_(file), metadata_(std::move(metadata)) {}

  Metadata parse() const {
    Metadata parsed;
    if (const std::optional<std::string> type = text("type", metadata_)) {
      if (*type != "route" && *type != "grid") {
        fail("type", "is '" + *type + "', expected route or grid");
      }
      parsed.is_grid = *type == "grid";
      parsed.info.is_grid = *parsed.is_grid;
    }
    parsed.info.frame_rate_hz = number("frameRate", metadata_);
    if (parsed.info.frame_rate_hz && *parsed.info.frame_rate_hz <= 0.0) {
      // BoB writes 0 when the rate is unknown.
      parsed.info.frame_rate_hz.reset();
    }
    parsed.info.description = text("description", metadata_).value_or("");
    parsed.video_file = text("videoFile", metadata_).value_or("");
    if (const std::optional<double> flag = number("needsUnwrapping", metadata_)) {
      parsed.info.needs_unwrapping = *flag != 0.0;
    }

    const cv::FileNode camera = metadata_["camera"];
    if (camera.isMap()) {
      parsed.info.camera_name = text("name", camera).value_or("");
      parsed.info.image_size = resolution(camera["resolution"]);
      // BoB: "If needsUnwrapping is not explicitly set then assume that if the camera used was
      // panoramic then we want to unwrap it."
      if (!parsed.info.needs_unwrapping) {
        if (const std::optional<double> panoramic = number("isPanoramic", camera)) {
          parsed.info.needs_unwrapping = *panoramic != 0.0;
        }
      }
    } else if (!camera.empty()) {
      fail("camera", "is not a map");
    }
    return parsed;
  }

 private:
  std::optional<std::string> text(const char* key, const cv::FileNode& parent) const {
    const cv::FileNode node = parent[key];
    if (node.empty()) return std::nullopt;
    if (!node.isString()) fail(key, "is not text");
    return static_cast<std::string>(node);
  }

  std::optional<double> number(const char* key, const cv::FileNode& parent) const {
    const cv::FileNode node = parent[key];
    if (node.empty()) return std::nullopt;
    if (!node.isInt() && !node.isReal()) fail(key, "is not a number");
    const auto value = static_cast<double>(node);
    if (!std::isfinite(value)) fail(key, "is not a finite number");  // OpenCV reads .nan, .inf
    return value;
  }

  cv::Size resolution(const cv::FileNode& node) const {
    if (node.empty()) return {};
    if (!node.isSeq() || node.size() != 2 || !node[0].isInt() || !node[1].isInt() ||
        static_cast<int>(node[0]) < 1 || static_cast<int>(node[1]) < 1) {
      fail("camera.resolution", "is not [width, height] in pixels");
    }
    return {static_cast<int>(node[0]), static_cast<int>(node[1])};
  }

  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    throw InputError(file_.string() + ": metadata." + key + " " + problem);
  }

  std::filesystem::path file_;
  cv::FileNode metadata_;
};

// BoB's metadata is a few hundred bytes, nested three levels deep. OpenCV's YAML parser
// recurses once per level of nesting, so a small file of 50,000 brackets overflows the stack
// (SIGSEGV, no exception): the size and depth are bounded here, before OpenCV sees the text.
constexpr std::size_t kMaxMetadataBytes = 64 * 1024;
constexpr int kMaxMetadataDepth = 32;

// An upper bound of the nesting OpenCV would follow: flow brackets ([ and {) still open, plus,
// at the start of each line, its indentation and its "- " sequence markers (each of which can
// open a block collection). Brackets inside a quoted scalar or a comment are text; a quote or
// comment ends at the end of its line here, so that the bound errs only on the safe side.
void check_nesting(const std::string& text, const std::filesystem::path& file) {
  if (text.size() > kMaxMetadataBytes) {
    throw InputError(file.string() + ": " + std::to_string(text.size()) +
                     " bytes, too large for BoB metadata (at most " +
                     std::to_string(kMaxMetadataBytes) + ")");
  }
  int flow_depth = 0;
  int line_depth = 0;  // indentation and sequence markers of the current line
  bool line_start = true;
  char quote = 0;     // the quote character of a quoted scalar being read
  char previous = 0;  // the last character outside quotes on this line that was not blank
  bool blank_before = true;
  bool comment = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    const bool blank = c == ' ' || c == '\t' || c == '\r';
    if (c == '\n') {
      line_start = blank_before = true;
      line_depth = 0;
      quote = previous = 0;
      comment = false;
      continue;
    }
    if (line_start) {
      if (blank ||
          (c == '-' && i + 1 < text.size() && (text[i + 1] == ' ' || text[i + 1] == '\t'))) {
        ++line_depth;
      } else {
        line_start = false;
      }
    }
    if (comment) continue;
    if (quote != 0) {
      if (c == quote) quote = 0;
    } else if ((c == '"' || c == '\'') && (previous == 0 || std::strchr(":-[{,", previous))) {
      quote = c;
    } else if (c == '#' && blank_before) {
      comment = true;
    } else if (c == '[' || c == '{') {
      ++flow_depth;
    } else if ((c == ']' || c == '}') && flow_depth > 0) {
      --flow_depth;
    }
    if (!blank && quote == 0) previous = c;
    blank_before = blank;
    if (flow_depth + line_depth > kMaxMetadataDepth) {
      throw InputError(file.string() + ": nested more than " + std::to_string(kMaxMetadataDepth) +
                       " levels deep (indentation included), not BoB metadata");
    }
  }
}

}  // namespace

std::optional<Metadata> read_metadata(const std::filesystem::path& yaml_file) {
  std::error_code error;
  if (!std::filesystem::exists(yaml_file, error)) return std::nullopt;
  std::ifstream stream(yaml_file, std::ios::binary);
  if (!stream) throw InputError(yaml_file.string() + ": cannot open");
  std::ostringstream file_text;
  file_text << stream.rdbuf();
  if (stream.bad()) throw InputError(yaml_file.string() + ": read error");
  check_nesting(file_text.str(), yaml_file);
  // As BoB does: prepend the directive, so that files written without it (by hand, or by BoB's
  // unwrap()) parse too; OpenCV skips the file's own directive line if it has one.
  const std::string content = "%YAML:1.0\n" + file_text.str();
  try {
    const cv::FileStorage storage(
        content, cv::FileStorage::READ | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
    const cv::FileNode metadata = storage["metadata"];
    if (!metadata.isMap()) throw InputError(yaml_file.string() + ": no 'metadata' map");
    return MetadataParser(yaml_file, metadata).parse();
  } catch (const cv::Exception& e) {
    throw InputError(yaml_file.string() + ": cannot parse YAML (" + e.err + ")");
  } catch (const std::length_error&) {
    // OpenCV's YAML parser, given a key with no name ("   :x" in a map), asks for a string of
    // negative length (found by tests/fuzz/bob_metadata_fuzz.cpp).
    throw InputError(yaml_file.string() + ": cannot parse YAML (a key with no name?)");
  }
}

std::string metadata_yaml(const DatabaseInfo& info, bool greyscale) {
  cv::FileStorage storage(".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
  storage << "metadata"
          << "{";
  storage << "type" << (info.is_grid ? "grid" : "route");
  storage << "camera"
          << "{";
  storage << "name" << info.camera_name;
  storage << "resolution"
          << "[:" << info.image_size.width << info.image_size.height << "]";
  // BoB's reader takes isPanoramic (a raw omnidirectional camera) for needsUnwrapping when
  // that key is absent, so the two must agree.
  storage << "isPanoramic" << (info.needs_unwrapping.value_or(false) ? 1 : 0);
  storage << "}";
  if (info.needs_unwrapping) storage << "needsUnwrapping" << (*info.needs_unwrapping ? 1 : 0);
  storage << "isGreyscale" << (greyscale ? 1 : 0);
  if (info.frame_rate_hz) storage << "frameRate" << *info.frame_rate_hz;
  if (!info.description.empty()) storage << "description" << info.description;
  storage << "}";
  return storage.releaseAndGetString();
}

}  // namespace omninav::io::bob
