#include "omninav/memory/visual_memory.hpp"

#include <cmath>

#include "omninav/core/errors.hpp"

namespace omninav::memory {

std::string to_string(HeadingSource source) {
  switch (source) {
    case HeadingSource::kTruth:
      return "truth";
    case HeadingSource::kCompass:
      return "compass";
    case HeadingSource::kNone:
      break;
  }
  return "none";
}

HeadingSource heading_source_from_string(const std::string& text) {
  if (text == "none") return HeadingSource::kNone;
  if (text == "truth") return HeadingSource::kTruth;
  if (text == "compass") return HeadingSource::kCompass;
  throw InputError("heading source '" + text + "' is not one of: none, truth, compass");
}

std::string to_string(EdgeKind kind) {
  return kind == EdgeKind::kListed ? "listed" : "sequence";
}

EdgeKind edge_kind_from_string(const std::string& text) {
  if (text == "sequence") return EdgeKind::kSequence;
  if (text == "listed") return EdgeKind::kListed;
  throw InputError("edge kind '" + text + "' is not one of: sequence, listed");
}

VisualMemory::VisualMemory(MapParameters parameters) : parameters_(std::move(parameters)) {}

const Place& VisualMemory::place(PlaceIndex index) const {
  if (index >= place_count()) {
    throw UsageError("no place " + std::to_string(index) + " in a map of " +
                     std::to_string(place_count()));
  }
  return graph_[index];
}

void VisualMemory::set_exploration_spacing_m(double metres) {
  if (!std::isfinite(metres) || metres <= 0.0) {
    throw UsageError("an exploration spacing of " + std::to_string(metres) +
                     " m: it must be a positive distance");
  }
  exploration_spacing_m_ = metres;
}

void VisualMemory::set_grid_spacing_m(double metres) {
  if (!std::isfinite(metres) || metres <= 0.0) {
    throw UsageError("a grid spacing of " + std::to_string(metres) +
                     " m: it must be a positive distance");
  }
  grid_spacing_m_ = metres;
}

void VisualMemory::set_lattice_positions(const std::vector<Eigen::Vector2d>& lattice_positions) {
  if (lattice_positions.size() != place_count()) {
    throw UsageError(std::to_string(lattice_positions.size()) + " lattice positions for a map of " +
                     std::to_string(place_count()) + " places");
  }
  for (PlaceIndex i = 0; i < place_count(); ++i) graph_[i].lattice_position = lattice_positions[i];
}

void VisualMemory::clear_lattice_positions() {
  for (PlaceIndex i = 0; i < place_count(); ++i) graph_[i].lattice_position.reset();
  lattice_quality_.reset();
}

std::size_t VisualMemory::add_run(Run run) {
  runs_.push_back(std::move(run));
  return runs_.size() - 1;
}

Run& VisualMemory::run(std::size_t run_index) {
  if (run_index >= runs_.size()) {
    throw UsageError("no run " + std::to_string(run_index) + " in a map of " +
                     std::to_string(runs_.size()));
  }
  return runs_[run_index];
}

void VisualMemory::record_run_progress(std::size_t run_index, int frames, int places) {
  Run& r = run(run_index);
  r.frames = frames;
  r.places = places;
}

void VisualMemory::set_run_heading_source(std::size_t run_index, HeadingSource source) {
  run(run_index).heading_source = source;
}

void VisualMemory::add_run_note(std::size_t run_index, const std::string& note) {
  if (!note.empty()) run(run_index).description += "; " + note;
}

PlaceIndex VisualMemory::add_place(Place place) {
  const signature::Signature& s = place.signature;
  const int channels = parameters_.signature.colour == signature::ColourMode::kLuminance ? 1 : 3;
  if (s.channels != channels || s.components != parameters_.signature.components) {
    throw UsageError("a place's signature (" + std::to_string(s.channels) + " channel(s), " +
                     std::to_string(s.components) + " components) does not match the map's (" +
                     signature::to_string(parameters_.signature.colour) + ", " +
                     std::to_string(parameters_.signature.components) + " components)");
  }
  if (parameters_.panorama_rows == 0) parameters_.panorama_rows = s.rows;
  if (s.rows != parameters_.panorama_rows) {
    throw UsageError("a panorama of " + std::to_string(s.rows) +
                     " rows cannot join a map whose panoramas have " +
                     std::to_string(parameters_.panorama_rows) + " rows");
  }
  if (s.magnitude.size() != s.size() || s.phase_rad.size() != s.size()) {
    throw UsageError("a place's signature holds the wrong number of values");
  }
  return boost::add_vertex(std::move(place), graph_);
}

void VisualMemory::add_edge(PlaceIndex from, PlaceIndex to, const Edge& edge) {
  if (from >= place_count() || to >= place_count()) {
    throw UsageError("an edge " + std::to_string(from) + " -> " + std::to_string(to) +
                     " names a place the map does not have (" + std::to_string(place_count()) +
                     " places)");
  }
  edge_order_.push_back({from, boost::out_degree(from, graph_)});
  boost::add_edge(from, to, edge, graph_);
}

std::vector<VisualMemory::EdgeRef> VisualMemory::edges() const {
  std::vector<EdgeRef> out;
  out.reserve(edge_order_.size());
  for (const EdgeSlot& slot : edge_order_) {
    const auto first = boost::out_edges(slot.from, graph_).first;
    const Graph::edge_descriptor e =
        *std::next(first, static_cast<std::ptrdiff_t>(slot.out_position));
    out.push_back({slot.from, boost::target(e, graph_), &graph_[e]});
  }
  return out;
}

bool VisualMemory::all_have_truth() const {
  if (place_count() == 0) return false;
  for (PlaceIndex i = 0; i < place_count(); ++i) {
    if (!graph_[i].truth) return false;
  }
  return true;
}

bool VisualMemory::all_have_lattice() const {
  if (place_count() == 0) return false;
  for (PlaceIndex i = 0; i < place_count(); ++i) {
    if (!graph_[i].lattice_position) return false;
  }
  return true;
}

std::size_t VisualMemory::bytes() const {
  std::size_t total = sizeof(*this);
  for (PlaceIndex i = 0; i < place_count(); ++i) {
    const Place& p = graph_[i];
    total += sizeof(Place) + p.signature.magnitude.capacity() * sizeof(float) +
             p.signature.phase_rad.capacity() * sizeof(float) + p.thumbnail_png.capacity() +
             p.source.capacity();
  }
  // Per vertex and per edge, adjacency_list keeps an out- and in-edge list entry and the edge.
  total += edge_count() * (sizeof(Edge) + 4 * sizeof(void*));
  return total;
}

}  // namespace omninav::memory
