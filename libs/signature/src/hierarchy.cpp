#include "omninav/signature/hierarchy.hpp"

#include <algorithm>
#include <numeric>

#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
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
  section.read("candidate_similarity", params.candidate_similarity, 0.0, 1000.0);
  section.read("max_probes", params.max_probes, 0, 100000);
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

SearchResult SignatureIndex::search(const Signature& query, double candidate_similarity,
                                    std::size_t top_k_count, int max_probes) const {
  check(query, "the query's signature");
  SearchResult result;
  if (size_ == 0) {
    for (int m : levels_) result.levels.push_back({m, 0, 0.0, 0.0, {}});
    return result;
  }
  const Eigen::Index n = static_cast<Eigen::Index>(size_);

  // Level 1: every place, one vectorised L1 over the first band.
  const Eigen::RowVectorXf q0 = query_band(query, 0);
  const Eigen::VectorXf coarse = (bands_[0].topRows(n).rowwise() - q0).cwiseAbs().rowwise().sum();
  std::vector<std::uint32_t> evaluated(size_);
  std::iota(evaluated.begin(), evaluated.end(), 0u);
  std::vector<float> dis(coarse.data(), coarse.data() + n);

  // The probes: the places most unlike the query at level 1, for Max Dis further down.
  std::vector<std::uint32_t> probes;
  std::vector<float> probe_dis;
  {
    // One pass keeping the `count` largest in a heap whose top is the smallest kept: O(N).
    const std::size_t count = std::min<std::size_t>(static_cast<std::size_t>(max_probes), size_);
    const auto smaller_first = [&](std::uint32_t a, std::uint32_t b) {
      return dis[a] > dis[b] || (dis[a] == dis[b] && a < b);
    };
    std::vector<std::uint32_t> heap;
    heap.reserve(count + 1);
    for (std::uint32_t i = 0; i < size_ && count > 0; ++i) {
      if (heap.size() < count) {
        heap.push_back(i);
        std::push_heap(heap.begin(), heap.end(), smaller_first);
      } else if (smaller_first(i, heap.front())) {
        std::pop_heap(heap.begin(), heap.end(), smaller_first);
        heap.back() = i;
        std::push_heap(heap.begin(), heap.end(), smaller_first);
      }
    }
    std::sort_heap(heap.begin(), heap.end(), smaller_first);
    probes = heap;
    for (std::uint32_t p : probes) probe_dis.push_back(dis[p]);
  }

  // Places compared at the current level, with their running Dis, and whether each may be a
  // candidate (was one at the previous level). Besides the candidates, the best top_k places of
  // the previous level are carried, so that the finest level can always report top_k places;
  // they rank but never become candidates.
  std::vector<char> eligible;  // all eligible at the first level
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    if (l > 0) {
      const Eigen::RowVectorXf q = query_band(query, l);
      const std::vector<Candidate>& previous = result.levels.back().candidates;
      std::vector<std::uint32_t> carried;
      std::vector<float> carried_dis;
      std::vector<char> carried_eligible;
      for (const Candidate& c : previous) {
        carried.push_back(c.place);
        carried_dis.push_back(c.dissimilarity);
        carried_eligible.push_back(1);
      }
      if (previous.size() < top_k_count) {
        for (const Candidate& c :
             top_k(evaluated, dis, 0.0, 0.0, std::min(top_k_count, evaluated.size()))) {
          if (std::none_of(previous.begin(), previous.end(),
                           [&](const Candidate& p) { return p.place == c.place; })) {
            carried.push_back(c.place);
            carried_dis.push_back(c.dissimilarity);
            carried_eligible.push_back(0);
          }
        }
      }
      for (std::size_t i = 0; i < carried.size(); ++i) {
        carried_dis[i] += band_distance(l, q, carried[i]);
      }
      evaluated = std::move(carried);
      dis = std::move(carried_dis);
      eligible = std::move(carried_eligible);
      for (std::size_t i = 0; i < probes.size(); ++i) {
        probe_dis[i] += band_distance(l, q, probes[i]);
      }
    }
    LevelResult level;
    level.components = levels_[l];
    level.evaluated = evaluated.size();
    const auto [lo, hi] = std::minmax_element(dis.begin(), dis.end());
    level.min_dissimilarity = lo == dis.end() ? 0.0 : *lo;
    level.max_dissimilarity = hi == dis.end() ? 0.0 : *hi;
    for (float p : probe_dis) {
      level.max_dissimilarity = std::max<double>(level.max_dissimilarity, p);
    }
    level.candidates = select(evaluated, dis, l == 0 ? nullptr : &eligible, level.min_dissimilarity,
                              level.max_dissimilarity, candidate_similarity);
    if (l + 1 == levels_.size()) {
      result.best =
          top_k(evaluated, dis, level.min_dissimilarity, level.max_dissimilarity, top_k_count);
    }
    result.levels.push_back(std::move(level));
  }
  return result;
}

}  // namespace omninav::signature
