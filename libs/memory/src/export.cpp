#include "omninav/memory/export.hpp"

#include <boost/graph/graphml.hpp>
#include <boost/property_map/function_property_map.hpp>
#include <cmath>
#include <limits>
#include <optional>

#include "omninav/core/angles.hpp"
#include "omninav/core/csv.hpp"
#include "omninav/core/format.hpp"

namespace omninav::memory {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Ten significant digits; empty for a missing value.
std::string number(std::optional<double> value) {
  if (!value || !std::isfinite(*value)) return "";
  return general(*value, 10);
}

std::optional<double> degrees(std::optional<double> radians) {
  if (!radians) return std::nullopt;
  return rad_to_deg(*radians);
}

}  // namespace

void write_places_csv(const VisualMemory& memory, std::ostream& out) {
  out << "place_id,run_id,source,frame_index,time_s,heading_deg,heading_source,truth_x_m,"
         "truth_y_m,truth_z_m,truth_heading_deg,lattice_x,lattice_y\n";
  for (PlaceIndex i = 0; i < memory.place_count(); ++i) {
    const Place& p = memory.place(i);
    out << i << ',' << p.run << ',' << csv_field(p.source) << ',' << p.frame_index << ','
        << number(p.time_s) << ',' << number(degrees(p.heading_rad)) << ','
        << to_string(p.heading_source) << ',';
    if (p.truth) {
      out << number(p.truth->x_m) << ',' << number(p.truth->y_m) << ',' << number(p.truth->z_m)
          << ',' << number(rad_to_deg(p.truth->heading_rad)) << ',';
    } else {
      out << ",,,,";
    }
    if (p.lattice_position) {
      out << number(p.lattice_position->x()) << ',' << number(p.lattice_position->y());
    } else {
      out << ',';
    }
    out << '\n';
  }
}

void write_edges_csv(const VisualMemory& memory, std::ostream& out) {
  out << "edge_id,from_place,to_place,kind,dissimilarity,relative_heading_deg,heading_confidence,"
         "motion_bearing_deg,motion_bearing_stddev_deg,parallax_deg\n";
  std::size_t id = 0;
  for (const VisualMemory::EdgeRef& ref : memory.edges()) {
    const Edge& e = *ref.edge;
    out << id++ << ',' << ref.from << ',' << ref.to << ',' << to_string(e.kind) << ','
        << number(e.dissimilarity) << ',' << number(rad_to_deg(e.relative_heading_rad)) << ','
        << number(e.heading_confidence) << ',' << number(degrees(e.motion_bearing_rad)) << ','
        << number(rad_to_deg(e.motion_bearing_stddev_rad)) << ','
        << number(rad_to_deg(e.parallax_rad)) << '\n';
  }
}

void write_graphml(const VisualMemory& memory, std::ostream& out) {
  using Vertex = boost::graph_traits<Graph>::vertex_descriptor;
  using EdgeDescriptor = boost::graph_traits<Graph>::edge_descriptor;
  const Graph& graph = memory.graph();
  boost::dynamic_properties properties;
  const auto vertex_number = [&](const std::string& name, auto get) {
    properties.property(
        name, boost::make_function_property_map<Vertex, double>(
                  [&graph, get](Vertex v) -> double { return get(graph[v]).value_or(kNaN); }));
  };
  const auto vertex_text = [&](const std::string& name, auto get) {
    properties.property(name, boost::make_function_property_map<Vertex, std::string>(
                                  [&graph, get](Vertex v) { return get(graph[v]); }));
  };
  const auto edge_number = [&](const std::string& name, auto get) {
    properties.property(name, boost::make_function_property_map<EdgeDescriptor, double>(
                                  [&graph, get](EdgeDescriptor e) -> double {
                                    return get(graph[e]).value_or(kNaN);
                                  }));
  };
  using Opt = std::optional<double>;
  vertex_text("source", [](const Place& p) { return p.source; });
  vertex_number("run_id", [](const Place& p) { return Opt(p.run); });
  vertex_number("frame_index", [](const Place& p) { return Opt(p.frame_index); });
  vertex_number("time_s", [](const Place& p) { return p.time_s; });
  vertex_number("heading_deg", [](const Place& p) { return degrees(p.heading_rad); });
  vertex_text("heading_source", [](const Place& p) { return to_string(p.heading_source); });
  vertex_number("truth_x_m", [](const Place& p) { return p.truth ? Opt(p.truth->x_m) : Opt(); });
  vertex_number("truth_y_m", [](const Place& p) { return p.truth ? Opt(p.truth->y_m) : Opt(); });
  vertex_number("truth_heading_deg", [](const Place& p) {
    return p.truth ? Opt(rad_to_deg(p.truth->heading_rad)) : Opt();
  });
  vertex_number("lattice_x", [](const Place& p) {
    return p.lattice_position ? Opt(p.lattice_position->x()) : Opt();
  });
  vertex_number("lattice_y", [](const Place& p) {
    return p.lattice_position ? Opt(p.lattice_position->y()) : Opt();
  });
  properties.property("kind", boost::make_function_property_map<EdgeDescriptor, std::string>(
                                  [&graph](EdgeDescriptor e) { return to_string(graph[e].kind); }));
  edge_number("dissimilarity", [](const Edge& e) { return Opt(e.dissimilarity); });
  edge_number("relative_heading_deg",
              [](const Edge& e) { return Opt(rad_to_deg(e.relative_heading_rad)); });
  edge_number("heading_confidence", [](const Edge& e) { return Opt(e.heading_confidence); });
  edge_number("motion_bearing_deg", [](const Edge& e) { return degrees(e.motion_bearing_rad); });
  edge_number("motion_bearing_stddev_deg",
              [](const Edge& e) { return Opt(rad_to_deg(e.motion_bearing_stddev_rad)); });
  edge_number("parallax_deg", [](const Edge& e) { return Opt(rad_to_deg(e.parallax_rad)); });
  boost::write_graphml(out, graph, boost::get(boost::vertex_index, graph), properties, true);
}

}  // namespace omninav::memory
