#include "omninav/evaluation/query_localisation.hpp"

#include <string>

#include "omninav/core/errors.hpp"
#include "omninav/evaluation/home_vectors.hpp"
#include "omninav/navigation/memory_places.hpp"

namespace omninav::evaluation {
namespace {

const memory::VisualMemory& with_places(const memory::VisualMemory& map,
                                        const std::string& map_name) {
  if (map.place_count() == 0) throw InputError(map_name + ": the map has no places");
  return map;
}

}  // namespace

QueryLocaliser::QueryLocaliser(const memory::VisualMemory& map, const std::string& map_name,
                               const memory::LocalisationParams& params,
                               const navigation::RouteParams& route,
                               const QueryLocalisationOptions& options)
    : map_(with_places(map, map_name)),
      localiser_(map, params),
      match_limit_(navigation::match_limit(map, route)),
      exhaustive_(options.exhaustive) {
  if (map.all_have_truth()) score_.emplace(map);
  if (options.home_vector) warping_.emplace(*options.home_vector, options.panorama);
}

signature::Signature QueryLocaliser::signature_of(const io::Frame& frame) {
  return localiser_.signature_of(frame.image, frame.source);
}

QueryLocalisation QueryLocaliser::localise(const io::Frame& frame,
                                           const signature::Signature& signature) {
  QueryLocalisation q;
  q.source = frame.source;
  q.truth = frame.truth;
  q.result =
      exhaustive_ ? localiser_.localise_exhaustive(signature) : localiser_.localise(signature);
  q.no_match = navigation::no_match_reason(q.result, match_limit_);
  if (q.no_match) {
    q.result.best.clear();
    q.result.position.reset();
  }
  if (score_ && q.truth) q.score = score_->add(q.result, *q.truth);
  if (warping_ && !q.result.best.empty()) {
    const int best = q.result.best.front().place;
    q.home = home_vector_to_place(*warping_, map_.place(best), "place " + std::to_string(best),
                                  frame.image, frame.source);
  }
  return q;
}

}  // namespace omninav::evaluation
