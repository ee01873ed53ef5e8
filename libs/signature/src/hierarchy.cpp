#include "omninav/signature/hierarchy.hpp"

#include <algorithm>
#include <numeric>

#include "omninav/core/best_k.hpp"
#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/param_check.hpp"
#include "omninav/core/parse.hpp"

namespace omninav::signature {

std::vector<int> parse_levels(const std::string& text, const std::string& where) {
  std::vector<int> levels;
  for (const std::string& field : split(text, ',')) {
    int value = 0;
    try {
      value = parse_int(field, where);
    } catch (const InputError& error) {
      throw UsageError(error.what());
    }
    if (value < 1) throw UsageError(where + ": level " + field + " must be at least 1");
    if (!levels.empty() && value <= levels.back()) {
      throw UsageError(where + ": levels must increase, got '" + text + "'");
    }
    levels.push_back(value);
  }
  if (levels.empty()) throw UsageError(where + ": no levels given");
  return levels;
}

void load_hierarchy_params(const ConfigReader& section, HierarchyParams& params) {
  std::string levels;
  for (int level : params.levels) {
    if (!levels.empty()) levels += ',';
    levels += std::to_string(level);
  }
  section.read("levels", levels, {});
  try {
    params.levels = parse_levels(levels, section.source_name() + ": key 'levels'");
  } catch (const UsageError& error) {
    throw ConfigError(error.what());
  }
  section.read("candidate_similarity", params.candidate_similarity);
  section.read("max_probes", params.max_probes);
  check_loaded(section.source_name(), [&] { params.check(); });
}

void HierarchyParams::check() const {
  if (levels.empty()) throw UsageError("key 'localisation.levels': no levels given");
  for (std::size_t l = 0; l < levels.size(); ++l) {
    if (levels[l] < 1 || (l > 0 && levels[l] <= levels[l - 1])) {
      throw UsageError("key 'localisation.levels' must be increasing and each at least 1");
    }
  }
  check_range("localisation.candidate_similarity", candidate_similarity, 0.0, 1000.0);
  check_range("localisation.max_probes", max_probes, 0, 100000);
}

SignatureIndex::SignatureIndex(int rows, int channels, std::vector<int> levels,
                               ComponentWeights weights)
    : rows_(rows),
      channels_(channels),
      lines_(rows * channels),
      levels_(std::move(levels)),
      weights_(std::move(weights)) {
  if (levels_.empty()) throw UsageError("a signature index needs at least one level");
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    if (levels_[l] < 1 || (l > 0 && levels_[l] <= levels_[l - 1])) {
      throw UsageError("index levels must be increasing and at least 1");
    }
  }
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    const int first = l == 0 ? 0 : levels_[l - 1];
    bands_.emplace_back(0, static_cast<Eigen::Index>(lines_) * (levels_[l] - first));
  }
}

void SignatureIndex::check(const Signature& signature, const char* what) const {
  if (signature.rows != rows_ || signature.channels != channels_) {
    throw UsageError(std::string(what) + " has " + std::to_string(signature.rows) + " rows x " +
                     std::to_string(signature.channels) + " channels; the map's signatures have " +
                     std::to_string(rows_) + " x " + std::to_string(channels_));
  }
  if (signature.components < levels_.back()) {
    throw UsageError(std::string(what) + " holds " + std::to_string(signature.components) +
                     " components; the finest level compares " + std::to_string(levels_.back()));
  }
}

void SignatureIndex::reserve(std::size_t places) {
  if (places <= static_cast<std::size_t>(bands_[0].rows())) return;
  for (Band& band : bands_) band.conservativeResize(static_cast<Eigen::Index>(places), band.cols());
}

Eigen::RowVectorXf SignatureIndex::query_band(const Signature& query, std::size_t level) const {
  const int first = level == 0 ? 0 : levels_[level - 1];
  const int count = levels_[level] - first;
  Eigen::RowVectorXf out(static_cast<Eigen::Index>(lines_) * count);
  for (int line = 0; line < lines_; ++line) {
    for (int j = 0; j < count; ++j) {
      out[static_cast<Eigen::Index>(line) * count + j] =
          static_cast<float>(weights_[first + j]) * query.magnitude[query.at(line, first + j)];
    }
  }
  return out;
}

std::uint32_t SignatureIndex::add(const Signature& signature) {
  check(signature, "a place's signature");
  if (size_ == static_cast<std::size_t>(bands_[0].rows())) {
    reserve(std::max<std::size_t>(64, 2 * size_));
  }
  for (std::size_t l = 0; l < bands_.size(); ++l) {
    bands_[l].row(static_cast<Eigen::Index>(size_)) = query_band(signature, l);
  }
  return static_cast<std::uint32_t>(size_++);
}

float SignatureIndex::band_distance(std::size_t level, const Eigen::RowVectorXf& q,
                                    std::uint32_t place) const {
  return (bands_[level].row(place) - q).cwiseAbs().sum();
}

std::size_t SignatureIndex::bytes() const {
  std::size_t total = 0;
  for (const Band& band : bands_) total += static_cast<std::size_t>(band.size()) * sizeof(float);
  return total;
}

namespace {

// Places whose similarity reaches the threshold (among those `eligible`, when given), best
// first.
std::vector<Candidate> select(const std::vector<std::uint32_t>& places,
                              const std::vector<float>& dis, const std::vector<char>* eligible,
                              double min_dis, double max_dis, double threshold) {
  std::vector<Candidate> out;
  for (std::size_t i = 0; i < places.size(); ++i) {
    if (eligible != nullptr && !(*eligible)[i]) continue;
    const double sim = similarity_0_1000(dis[i], min_dis, max_dis);
    if (sim >= threshold) {
      out.push_back({places[i], dis[i], static_cast<float>(sim)});
    }
  }
  std::sort(out.begin(), out.end(), [](const Candidate& a, const Candidate& b) {
    return a.dissimilarity < b.dissimilarity ||
           (a.dissimilarity == b.dissimilarity && a.place < b.place);
  });
  return out;
}

std::vector<Candidate> top_k(const std::vector<std::uint32_t>& places,
                             const std::vector<float>& dis, double min_dis, double max_dis,
                             std::size_t k) {
  std::vector<std::size_t> order(places.size());
  std::iota(order.begin(), order.end(), 0);
  const auto better = [&](std::size_t a, std::size_t b) {
    return dis[a] < dis[b] || (dis[a] == dis[b] && places[a] < places[b]);
  };
  const std::size_t count = std::min(k, order.size());
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(count), order.end(),
                    better);
  std::vector<Candidate> out;
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t j = order[i];
    out.push_back(
        {places[j], dis[j], static_cast<float>(similarity_0_1000(dis[j], min_dis, max_dis))});
  }
  return out;
}

}  // namespace

Eigen::VectorXf SignatureIndex::dissimilarities(const Signature& query, std::size_t level) const {
  check(query, "the query's signature");
  if (level >= levels_.size()) throw UsageError("no such level " + std::to_string(level));
  const Eigen::Index n = static_cast<Eigen::Index>(size_);
  Eigen::VectorXf total = Eigen::VectorXf::Zero(n);
  for (std::size_t l = 0; l <= level; ++l) {
    const Eigen::RowVectorXf q = query_band(query, l);
    total += (bands_[l].topRows(n).rowwise() - q).cwiseAbs().rowwise().sum();
  }
  return total;
}

SearchResult SignatureIndex::search_exhaustive(const Signature& query, double candidate_similarity,
                                               std::size_t top_k_count) const {
  check(query, "the query's signature");
  SearchResult result;
  std::vector<std::uint32_t> all(size_);
  std::iota(all.begin(), all.end(), 0u);
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    const Eigen::VectorXf dis_vector = dissimilarities(query, l);
    const std::vector<float> dis(dis_vector.data(), dis_vector.data() + dis_vector.size());
    LevelResult level;
    level.components = levels_[l];
    level.evaluated = size_;
    if (!dis.empty()) {
      const auto [lo, hi] = std::minmax_element(dis.begin(), dis.end());
      level.min_dissimilarity = *lo;
      level.max_dissimilarity = *hi;
    }
    level.candidates = select(all, dis, nullptr, level.min_dissimilarity, level.max_dissimilarity,
                              candidate_similarity);
    if (l + 1 == levels_.size()) {
      result.best = top_k(all, dis, level.min_dissimilarity, level.max_dissimilarity, top_k_count);
    }
    result.levels.push_back(std::move(level));
  }
  return result;
}

namespace {

// The places compared at one level, with their running Dis, and whether each may be a candidate
// (was one at the previous level; unused at the first level, where all may).
struct Compared {
  std::vector<std::uint32_t> places;
  std::vector<float> dis;
  std::vector<char> eligible;
};

// The `count` places most unlike the query at the first level (largest Dis first, ties by
// index), kept in one O(N) pass: the probes for Max Dis further down.
std::vector<std::uint32_t> most_unlike(const std::vector<float>& dis, std::size_t count) {
  const auto larger_first = [&dis](std::uint32_t a, std::uint32_t b) {
    return dis[a] > dis[b] || (dis[a] == dis[b] && a < b);
  };
  BestK<std::uint32_t, decltype(larger_first)> most(count, larger_first);
  most.reserve();
  for (std::uint32_t i = 0; i < dis.size(); ++i) most.offer(i);
  return std::move(most).take_sorted();
}

// The places carried from a level to the next, their Dis so far: the level's candidates, and
// besides them its best top_k places, so that the finest level can always report top_k places;
// those rank but never become candidates.
Compared carried_from(const Compared& level, const std::vector<Candidate>& candidates,
                      std::size_t top_k_count) {
  Compared next;
  for (const Candidate& c : candidates) {
    next.places.push_back(c.place);
    next.dis.push_back(c.dissimilarity);
    next.eligible.push_back(1);
  }
  if (candidates.size() < top_k_count) {
    for (const Candidate& c :
         top_k(level.places, level.dis, 0.0, 0.0, std::min(top_k_count, level.places.size()))) {
      if (std::none_of(candidates.begin(), candidates.end(),
                       [&](const Candidate& p) { return p.place == c.place; })) {
        next.places.push_back(c.place);
        next.dis.push_back(c.dissimilarity);
        next.eligible.push_back(0);
      }
    }
  }
  return next;
}

// A level's Min Dis and Max Dis over the places compared, Max Dis over the probes too.
void set_range(const std::vector<float>& dis, const std::vector<float>& probe_dis,
               LevelResult& level) {
  const auto [lo, hi] = std::minmax_element(dis.begin(), dis.end());
  level.min_dissimilarity = lo == dis.end() ? 0.0 : *lo;
  level.max_dissimilarity = hi == dis.end() ? 0.0 : *hi;
  for (float p : probe_dis) level.max_dissimilarity = std::max<double>(level.max_dissimilarity, p);
}

}  // namespace

SearchResult SignatureIndex::search(const Signature& query, double candidate_similarity,
                                    std::size_t top_k_count, int max_probes) const {
  check(query, "the query's signature");
  SearchResult result;
  if (size_ == 0) {
    for (int m : levels_) result.levels.push_back({m, 0, 0.0, 0.0, {}});
    return result;
  }
  // Level 1: every place, one vectorised L1 over the first band.
  const Eigen::Index n = static_cast<Eigen::Index>(size_);
  const Eigen::VectorXf coarse =
      (bands_[0].topRows(n).rowwise() - query_band(query, 0)).cwiseAbs().rowwise().sum();
  Compared compared;
  compared.places.resize(size_);
  std::iota(compared.places.begin(), compared.places.end(), 0u);
  compared.dis.assign(coarse.data(), coarse.data() + n);
  const std::vector<std::uint32_t> probes =
      most_unlike(compared.dis, std::min<std::size_t>(static_cast<std::size_t>(max_probes), size_));
  std::vector<float> probe_dis;
  for (std::uint32_t p : probes) probe_dis.push_back(compared.dis[p]);

  for (std::size_t l = 0; l < levels_.size(); ++l) {
    if (l > 0) {
      // The next band added to the running Dis of the places carried and of the probes.
      const Eigen::RowVectorXf q = query_band(query, l);
      compared = carried_from(compared, result.levels.back().candidates, top_k_count);
      for (std::size_t i = 0; i < compared.places.size(); ++i) {
        compared.dis[i] += band_distance(l, q, compared.places[i]);
      }
      for (std::size_t i = 0; i < probes.size(); ++i) {
        probe_dis[i] += band_distance(l, q, probes[i]);
      }
    }
    LevelResult level;
    level.components = levels_[l];
    level.evaluated = compared.places.size();
    set_range(compared.dis, probe_dis, level);
    level.candidates =
        select(compared.places, compared.dis, l == 0 ? nullptr : &compared.eligible,
               level.min_dissimilarity, level.max_dissimilarity, candidate_similarity);
    if (l + 1 == levels_.size()) {
      result.best = top_k(compared.places, compared.dis, level.min_dissimilarity,
                          level.max_dissimilarity, top_k_count);
    }
    result.levels.push_back(std::move(level));
  }
  return result;
}

}  // namespace omninav::signature
