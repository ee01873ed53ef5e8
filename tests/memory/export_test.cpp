#include "omninav/memory/export.hpp"

#include <gtest/gtest.h>

#include <boost/graph/graphml.hpp>
#include <sstream>

#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/memory/memory_config.hpp"
#include "support/shared_data.hpp"

namespace omninav::memory {
namespace {

VisualMemory small_memory() {
  VisualMemory memory;
  memory.add_run(Run{0, "input", "2024-01-01T00:00:00Z", 3, 3, HeadingSource::kTruth, "test"});
  for (int i = 0; i < 3; ++i) {
    Place p;
    p.signature = {45, 1, 15, 360, std::vector<float>(675, 1.f), std::vector<float>(675, 0.f)};
    p.source = i == 1 ? "a \"quoted\", file.png" : "image_" + std::to_string(i) + ".png";
    p.frame_index = i;
    if (i != 2) {
      p.truth = CameraPose{0.5 * i, 1.0, 1.0, 0.5, 0.0, 0.0};
      p.heading_rad = 0.5;
      p.heading_source = HeadingSource::kTruth;
    }
    memory.add_place(std::move(p));
  }
  Edge e;
  e.dissimilarity = 12.5;
  e.relative_heading_rad = -0.25;
  e.motion_bearing_rad = 1.0;
  memory.add_edge(0, 1, e);
  e.motion_bearing_rad.reset();
  memory.add_edge(1, 2, e);
  return memory;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream stream(text);
  for (std::string line; std::getline(stream, line);) out.push_back(line);
  return out;
}

TEST(Export, PlacesCsvHasUnitsDegreesAndEmptyFieldsForMissingValues) {
  std::ostringstream out;
  write_places_csv(small_memory(), out);
  const auto rows = lines(out.str());
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0],
            "place_id,run_id,source,frame_index,time_s,heading_deg,heading_source,truth_x_m,"
            "truth_y_m,truth_z_m,truth_heading_deg,lattice_x,lattice_y");
  EXPECT_EQ(rows[1], "0,0,image_0.png,0,,28.64788976,truth,0,1,1,28.64788976,,");
  EXPECT_EQ(rows[2].substr(0, 34), "1,0,\"a \"\"quoted\"\", file.png\",1,,28");
  EXPECT_EQ(rows[3], "2,0,image_2.png,2,,,none,,,,,,");
}

TEST(Export, EdgesCsvInTheOrderAdded) {
  std::ostringstream out;
  write_edges_csv(small_memory(), out);
  const auto rows = lines(out.str());
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[1], "0,0,1,sequence,12.5,-14.32394488,0,57.29577951,0,0");
  EXPECT_EQ(rows[2], "1,1,2,sequence,12.5,-14.32394488,0,,0,0");
}

TEST(Export, GraphMlReadsBackWithBoost) {
  std::ostringstream out;
  write_graphml(small_memory(), out);
  // Read it back into a plain graph with Boost's own reader.
  using Plain = boost::adjacency_list<boost::vecS, boost::vecS, boost::directedS,
                                      boost::property<boost::vertex_name_t, std::string>,
                                      boost::property<boost::edge_weight_t, double>>;
  Plain graph;
  boost::dynamic_properties properties(boost::ignore_other_properties);
  properties.property("source", boost::get(boost::vertex_name, graph));
  properties.property("dissimilarity", boost::get(boost::edge_weight, graph));
  std::istringstream in(out.str());
  boost::read_graphml(in, graph, properties);
  EXPECT_EQ(boost::num_vertices(graph), 3u);
  EXPECT_EQ(boost::num_edges(graph), 2u);
  EXPECT_EQ(boost::get(boost::vertex_name, graph, 1), "a \"quoted\", file.png");
  EXPECT_EQ(boost::get(boost::edge_weight, graph, *boost::edges(graph).first), 12.5);
}

TEST(MemoryConfig, TheShippedFileLoadsAndUnknownKeysAreErrors) {
  const MemoryConfig config =
      load_memory_config(ConfigReader::from_file(omninav::testing::config_dir() / "memory.yaml"));
  EXPECT_EQ(config.map.signature.components, 15);
  EXPECT_EQ(config.localisation.hierarchy.levels, (std::vector<int>{2, 5, 15}));
  EXPECT_EQ(config.map.weights.alpha, (std::vector<double>{1.0}));
  EXPECT_THROW(
      load_memory_config(ConfigReader::from_string("signature: {component: 15}", "m.yaml")),
      ConfigError);
  EXPECT_THROW(
      load_memory_config(ConfigReader::from_string("exploration: {every_m: -1}", "m.yaml")),
      ConfigError);
  EXPECT_THROW(load_memory_config(ConfigReader::from_string("signature: {weights: 'a'}", "m.yaml")),
               ConfigError);
}

}  // namespace
}  // namespace omninav::memory
