#pragma once
// `omninav localise`'s pipeline, for any caller: each query frame localised in a map
// (memory::Localiser, Menegatti et al. 2004, §2.3), refused when its best place lies beyond
// route's and navigate's match limit (navigation::no_match_reason), scored against the map's
// ground truth when both have it (LocalisationScore), and with a home vector to its best place
// on request (min-warping, home_vectors.hpp). The command parses, calls this, prints and plots.

#include <optional>

#include "omninav/compass/min_warping.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/evaluation/localisation_output.hpp"
#include "omninav/evaluation/localisation_score.hpp"
#include "omninav/io/frame.hpp"
#include "omninav/memory/localisation.hpp"
#include "omninav/memory/visual_memory.hpp"
#include "omninav/navigation/route_planner.hpp"
#include "omninav/signature/signature.hpp"

namespace omninav::evaluation {

struct QueryLocalisationOptions {
  bool exhaustive = false;  // every place at every level (no pruning; for comparison)
  // Min-warping's parameters for a home vector from each query to its best place, with the
  // panorama geometry it reads the rows by (camera.yaml); none: no home vectors.
  std::optional<compass::MinWarpingParams> home_vector;
  PanoramaGeometry panorama;
};

class QueryLocaliser {
 public:
  // `map` must outlive this and hold places (InputError otherwise, naming `map_name`).
  // `params` and `route` as memory.yaml's localisation and navigation.yaml's route sections.
  QueryLocaliser(const memory::VisualMemory& map, const std::string& map_name,
                 const memory::LocalisationParams& params, const navigation::RouteParams& route,
                 const QueryLocalisationOptions& options);

  // The frame's signature, as localise() compares it (a figure of the query draws from it).
  signature::Signature signature_of(const io::Frame& frame);
  // One query: its localisation (emptied when it matches no place, with the reason), its
  // score when both it and the map have ground truth, and its home vector when asked for.
  QueryLocalisation localise(const io::Frame& frame, const signature::Signature& signature);

  const memory::Localiser& localiser() const { return localiser_; }
  // The scores of the queries so far; none when the map's places lack ground truth.
  const std::optional<LocalisationScore>& score() const { return score_; }

 private:
  const memory::VisualMemory& map_;
  memory::Localiser localiser_;
  double match_limit_;
  bool exhaustive_;
  std::optional<LocalisationScore> score_;
  std::optional<compass::MinWarping> warping_;
};

}  // namespace omninav::evaluation
