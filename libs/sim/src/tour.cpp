#include "omninav/sim/tour.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>

#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"

namespace omninav::sim {
namespace {

// The most raster cells a tour or a coverage measure may use (2000 x 2000): a field of 100 m at
// 5 cm.
constexpr double kMaxCells = 4e6;

std::string metres(double value) {
  return trimmed(value, 2);
}

// The floor's rectangle `area` (clipped to the floor) as a raster of square cells.
class Raster {
 public:
  Raster(const FloorBox& floor, const FloorBox& area, double cell_m, const std::string& where)
      : cell_m_(cell_m) {
    min_x_ = std::max(area.min_x_m, floor.min_x_m);
    min_y_ = std::max(area.min_y_m, floor.min_y_m);
    const double max_x = std::min(area.max_x_m, floor.max_x_m);
    const double max_y = std::min(area.max_y_m, floor.max_y_m);
    if (!(max_x > min_x_ && max_y > min_y_)) {
      throw UsageError(where + ": the rectangle x " + metres(area.min_x_m) + ".." +
                       metres(area.max_x_m) + ", y " + metres(area.min_y_m) + ".." +
                       metres(area.max_y_m) + " m (x0, y0, x1, y1) has no floor in it");
    }
    const double nx = std::ceil((max_x - min_x_) / cell_m),
                 ny = std::ceil((max_y - min_y_) / cell_m);
    if (nx * ny > kMaxCells) {
      throw UsageError(where + ": " + metres(max_x - min_x_) + " x " + metres(max_y - min_y_) +
                       " m at " + metres(cell_m) + " m cells is more than " +
                       std::to_string(static_cast<int>(kMaxCells)) +
                       " cells (restrict it with x0, y0, x1, y1, or widen lane_m)");
    }
    nx_ = std::max(1, static_cast<int>(nx));
    ny_ = std::max(1, static_cast<int>(ny));
  }

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  int size() const { return nx_ * ny_; }
  int index(int ix, int iy) const { return iy * nx_ + ix; }
  int ix(int cell) const { return cell % nx_; }
  int iy(int cell) const { return cell / nx_; }
  Eigen::Vector2d centre(int cell) const {
    return {min_x_ + (ix(cell) + 0.5) * cell_m_, min_y_ + (iy(cell) + 0.5) * cell_m_};
  }
  double cell_m() const { return cell_m_; }

  // The 4 neighbours of a cell inside the raster.
  template <typename Visit>
  void neighbours(int cell, Visit visit) const {
    const int x = ix(cell), y = iy(cell);
    if (x > 0) visit(cell - 1);
    if (x + 1 < nx_) visit(cell + 1);
    if (y > 0) visit(cell - nx_);
    if (y + 1 < ny_) visit(cell + nx_);
  }

 private:
  double cell_m_;
  double min_x_ = 0.0, min_y_ = 0.0;
  int nx_ = 0, ny_ = 0;
};

// Breadth-first search over the free cells from `source`: steps to every cell (-1 where none
// leads) and the cell each was reached from. Written here rather than with Boost.Graph's
// breadth_first_search: the raster is an implicit 4-neighbour grid that this walks without
// building a graph of its cells, and libs/sim sits on core alone (docs: the layers).
struct Search {
  std::vector<int> steps;
  std::vector<int> parent;
};

Search breadth_first(const Raster& raster, const std::vector<char>& free, int source) {
  Search search{std::vector<int>(raster.size(), -1), std::vector<int>(raster.size(), -1)};
  std::deque<int> queue{source};
  search.steps[source] = 0;
  while (!queue.empty()) {
    const int cell = queue.front();
    queue.pop_front();
    raster.neighbours(cell, [&](int next) {
      if (!free[next] || search.steps[next] >= 0) return;
      search.steps[next] = search.steps[cell] + 1;
      search.parent[next] = cell;
      queue.push_back(next);
    });
  }
  return search;
}

// A run of free cells along one lane of an area: driven from one end to the other.
struct Run {
  int area = 0;
  int first = 0, last = 0;  // end cells
  bool done = false;
};

class Planner {
 public:
  Planner(const World& world, const TourParams& params)
      : world_(world),
        params_(params),
        raster_(world.floor, params.area, params.cell_m, "trajectory '" + params.spec + "'") {}

  std::vector<Eigen::Vector2d> plan() {
    mark_free();
    const int start = main_part();
    make_runs();
    route_.push_back(raster_.centre(start));
    int at = start;
    int area = -1;
    for (;;) {
      const Search search = breadth_first(raster_, free_, at);
      // The nearest run of the area being covered, else of any area.
      int best = -1;
      bool best_from_first = true;
      for (int pass = 0; pass < 2 && best < 0; ++pass) {
        int best_steps = std::numeric_limits<int>::max();
        for (std::size_t r = 0; r < runs_.size(); ++r) {
          const Run& run = runs_[r];
          if (run.done || (pass == 0 && run.area != area)) continue;
          for (const bool from_first : {true, false}) {
            const int steps = search.steps[from_first ? run.first : run.last];
            if (steps >= 0 && steps < best_steps) {
              best_steps = steps;
              best = static_cast<int>(r);
              best_from_first = from_first;
            }
          }
        }
      }
      if (best < 0) break;
      Run& run = runs_[best];
      const int entry = best_from_first ? run.first : run.last;
      const int exit = best_from_first ? run.last : run.first;
      follow(path_cells(search, entry));
      follow(run_cells(entry, exit));
      run.done = true;
      area = run.area;
      at = exit;
    }
    return route_;
  }

 private:
  void mark_free() {
    free_.assign(raster_.size(), 0);
    int count = 0;
    for (int cell = 0; cell < raster_.size(); ++cell) {
      const Eigen::Vector2d c = raster_.centre(cell);
      free_[cell] = world_.is_free(c.x(), c.y(), params_.clearance_m) ? 1 : 0;
      count += free_[cell];
    }
    if (count == 0) {
      throw UsageError("trajectory '" + params_.spec +
                       "': clearance_m = " + metres(params_.clearance_m) +
                       " leaves no free floor in the toured rectangle (a robot that keeps that far "
                       "from every obstacle and the floor's edge has nowhere to drive)");
    }
  }

  // The part of the free space the tour drives in (the one holding the free cell nearest the
  // start); every other part larger than a lane's square makes the tour impossible. Cells of the
  // smaller parts are left out of the free space. Returns the start cell.
  int main_part() {
    std::vector<int> part(raster_.size(), -1);
    std::vector<std::vector<int>> parts;
    for (int cell = 0; cell < raster_.size(); ++cell) {
      if (!free_[cell] || part[cell] >= 0) continue;
      const int label = static_cast<int>(parts.size());
      parts.emplace_back();
      std::deque<int> queue{cell};
      part[cell] = label;
      while (!queue.empty()) {
        const int at = queue.front();
        queue.pop_front();
        parts.back().push_back(at);
        raster_.neighbours(at, [&](int next) {
          if (free_[next] && part[next] < 0) {
            part[next] = label;
            queue.push_back(next);
          }
        });
      }
    }
    int start = -1;
    double nearest = std::numeric_limits<double>::infinity();
    for (int cell = 0; cell < raster_.size(); ++cell) {
      if (!free_[cell]) continue;
      const double d = (raster_.centre(cell) - params_.start).norm();
      if (d < nearest) {
        nearest = d;
        start = cell;
      }
    }
    const double cell_area = raster_.cell_m() * raster_.cell_m();
    const double least_area = params_.lane_m * params_.lane_m;
    std::vector<std::string> unreachable;
    for (std::size_t p = 0; p < parts.size(); ++p) {
      if (static_cast<int>(p) == part[start]) continue;
      if (parts[p].size() * cell_area >= least_area) unreachable.push_back(describe(parts[p]));
      for (const int cell : parts[p]) free_[cell] = 0;
    }
    if (!unreachable.empty()) {
      std::string names;
      for (const std::string& name : unreachable) names += (names.empty() ? "" : "; ") + name;
      throw UsageError("trajectory '" + params_.spec + "': no free path (clearance_m " +
                       metres(params_.clearance_m) + ") leads from the start in " +
                       describe(parts[part[start]]) + " to " + names +
                       ": the free space falls into parts no doorway joins (restrict the tour "
                       "with x0, y0, x1, y1, or lower clearance_m)");
    }
    return start;
  }

  // A part of the free space by the regions it lies in and its extent: "room 3 (x 0.4..2.6,
  // y 5.1..7.9 m, 4.2 m²)".
  std::string describe(const std::vector<int>& cells) const {
    std::map<std::string, int> in_region;
    Eigen::Vector2d low = raster_.centre(cells.front()), high = low;
    for (const int cell : cells) {
      const Eigen::Vector2d c = raster_.centre(cell);
      low = low.cwiseMin(c);
      high = high.cwiseMax(c);
      if (const Region* region = world_.region_at(c.x(), c.y())) ++in_region[region->name];
    }
    std::string names;
    for (const auto& [name, count] : in_region) names += (names.empty() ? "" : " + ") + name;
    if (names.empty()) names = "the part";
    const double area_m2 = cells.size() * raster_.cell_m() * raster_.cell_m();
    return names + " (x " + metres(low.x()) + ".." + metres(high.x()) + ", y " + metres(low.y()) +
           ".." + metres(high.y()) + " m, " + trimmed(area_m2, 1) + " m²)";
  }

  // The areas covered one after the other: the world's regions (cells in none, such as
  // doorways, are only driven through), or the whole free space when it has none. Each area's
  // lanes run along its longer side, evenly spread between its extreme free cells at most lane_m
  // apart; each lane's runs of consecutive free cells are the runs to drive.
  void make_runs() {
    std::vector<std::vector<int>> areas(std::max<std::size_t>(1, world_.regions.size()));
    for (int cell = 0; cell < raster_.size(); ++cell) {
      if (!free_[cell]) continue;
      if (world_.regions.empty()) {
        areas[0].push_back(cell);
        continue;
      }
      const Eigen::Vector2d c = raster_.centre(cell);
      for (std::size_t r = 0; r < world_.regions.size(); ++r) {
        if (world_.regions[r].area.contains(c.x(), c.y())) {
          areas[r].push_back(cell);
          break;
        }
      }
    }
    for (std::size_t a = 0; a < areas.size(); ++a) {
      if (!areas[a].empty()) add_runs(static_cast<int>(a), areas[a]);
    }
  }

  void add_runs(int area, const std::vector<int>& cells) {
    std::vector<char> in_area(raster_.size(), 0);
    int low_x = raster_.nx(), high_x = -1, low_y = raster_.ny(), high_y = -1;
    for (const int cell : cells) {
      in_area[cell] = 1;
      low_x = std::min(low_x, raster_.ix(cell));
      high_x = std::max(high_x, raster_.ix(cell));
      low_y = std::min(low_y, raster_.iy(cell));
      high_y = std::max(high_y, raster_.iy(cell));
    }
    const bool along_x = high_x - low_x >= high_y - low_y;
    const int across_low = along_x ? low_y : low_x, across_high = along_x ? high_y : high_x;
    const int along_low = along_x ? low_x : low_y, along_high = along_x ? high_x : high_y;
    const double span_m = (across_high - across_low) * raster_.cell_m();
    const int lanes = static_cast<int>(std::ceil(span_m / params_.lane_m - 1e-9)) + 1;
    int previous = -1;
    for (int lane = 0; lane < lanes; ++lane) {
      const int across =
          lanes == 1 ? (across_low + across_high) / 2
                     : across_low + static_cast<int>(std::lround(double(across_high - across_low) *
                                                                 lane / (lanes - 1)));
      if (across == previous) continue;
      previous = across;
      int begin = -1;
      for (int along = along_low; along <= along_high + 1; ++along) {
        const int cell = along > along_high ? -1
                         : along_x          ? raster_.index(along, across)
                                            : raster_.index(across, along);
        const bool inside = cell >= 0 && in_area[cell];
        if (inside && begin < 0) begin = cell;
        if (!inside && begin >= 0) {
          const int end =
              along_x ? raster_.index(along - 1, across) : raster_.index(across, along - 1);
          runs_.push_back({area, begin, end, false});
          begin = -1;
        }
      }
    }
  }

  // The cells from the search's source to `target`, in order.
  std::vector<int> path_cells(const Search& search, int target) const {
    std::vector<int> cells;
    for (int cell = target; cell >= 0; cell = search.parent[cell]) cells.push_back(cell);
    std::reverse(cells.begin(), cells.end());
    return cells;
  }

  // The cells of a run from one end to the other.
  std::vector<int> run_cells(int from, int to) const {
    std::vector<int> cells;
    const int dx = raster_.ix(to) - raster_.ix(from), dy = raster_.iy(to) - raster_.iy(from);
    const int steps = std::max(std::abs(dx), std::abs(dy));
    for (int k = 0; k <= steps; ++k) {
      cells.push_back(raster_.index(raster_.ix(from) + (steps ? dx * k / steps : 0),
                                    raster_.iy(from) + (steps ? dy * k / steps : 0)));
    }
    return cells;
  }

  bool clear(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const {
    return world_.segment_is_free(a.x(), a.y(), b.x(), b.y(), params_.clearance_m);
  }

  // Appends the cells' centres to the route, keeping only the corners that a straight free
  // segment cannot skip (the cells are consecutive and free, so each step is free).
  void follow(const std::vector<int>& cells) {
    if (cells.size() < 2) return;
    std::size_t anchor = 0;
    while (anchor + 1 < cells.size()) {
      std::size_t reach = anchor + 1;
      while (reach + 1 < cells.size() &&
             clear(raster_.centre(cells[anchor]), raster_.centre(cells[reach + 1]))) {
        ++reach;
      }
      add(raster_.centre(cells[reach]));
      anchor = reach;
    }
  }

  void add(const Eigen::Vector2d& point) {
    if ((point - route_.back()).norm() < 1e-9) return;
    // A point in line with the last two only lengthens the last leg.
    if (route_.size() >= 2) {
      const Eigen::Vector2d a = route_[route_.size() - 2], b = route_.back();
      const Eigen::Vector2d ab = b - a, bp = point - b;
      const double cross = ab.x() * bp.y() - ab.y() * bp.x();
      if (std::abs(cross) < 1e-12 && ab.dot(bp) > 0.0) {
        route_.back() = point;
        return;
      }
    }
    route_.push_back(point);
  }

  const World& world_;
  const TourParams& params_;
  Raster raster_;
  std::vector<char> free_;
  std::vector<Run> runs_;
  std::vector<Eigen::Vector2d> route_;
};

}  // namespace

std::vector<Eigen::Vector2d> plan_tour(const World& world, const TourParams& params) {
  const std::string where = "trajectory '" + params.spec + "'";
  if (!(params.lane_m >= 0.05 && params.lane_m <= 100.0)) {
    throw UsageError(where + ": lane_m = " + metres(params.lane_m) +
                     " is out of range (valid: [0.05, 100] m between lanes)");
  }
  if (!(params.clearance_m >= 0.0 && params.clearance_m <= 10.0)) {
    throw UsageError(where + ": clearance_m = " + metres(params.clearance_m) +
                     " is out of range (valid: [0, 10] m)");
  }
  if (!(params.cell_m > 0.0 && params.cell_m <= params.lane_m / 3.0 + 1e-12)) {
    throw UsageError(where + ": cell_m must be positive and at most lane_m / 3");
  }
  return Planner(world, params).plan();
}

Coverage route_coverage(const World& world, const std::vector<Eigen::Vector2d>& route,
                        const FloorBox& area, double reach_m, double cell_m) {
  const Raster raster(world.floor, area, cell_m, "coverage");
  std::vector<char> covered(raster.size(), 0);
  const auto cover = [&](const Eigen::Vector2d& p) {
    const int reach = static_cast<int>(std::ceil(reach_m / cell_m)) + 1;
    const Eigen::Vector2d origin = raster.centre(0);
    const int cx = static_cast<int>(std::lround((p.x() - origin.x()) / cell_m));
    const int cy = static_cast<int>(std::lround((p.y() - origin.y()) / cell_m));
    for (int y = std::max(0, cy - reach); y <= std::min(raster.ny() - 1, cy + reach); ++y) {
      for (int x = std::max(0, cx - reach); x <= std::min(raster.nx() - 1, cx + reach); ++x) {
        const int cell = raster.index(x, y);
        if (!covered[cell] && (raster.centre(cell) - p).norm() <= reach_m) covered[cell] = 1;
      }
    }
  };
  for (std::size_t i = 0; i < route.size(); ++i) {
    if (i == 0) {
      cover(route[0]);
      continue;
    }
    // Between two points at most a cell apart, so that no stretch of the route is skipped.
    const Eigen::Vector2d from = route[i - 1], to = route[i];
    const int steps = std::max(1, static_cast<int>(std::ceil((to - from).norm() / cell_m)));
    for (int k = 1; k <= steps; ++k) cover(from + (to - from) * (double(k) / steps));
  }
  Coverage coverage;
  std::vector<double> free_in(world.regions.size(), 0.0), covered_in(world.regions.size(), 0.0);
  double free_cells = 0.0, covered_cells = 0.0;
  for (int cell = 0; cell < raster.size(); ++cell) {
    const Eigen::Vector2d c = raster.centre(cell);
    if (!world.is_free(c.x(), c.y())) continue;
    free_cells += 1.0;
    covered_cells += covered[cell];
    for (std::size_t r = 0; r < world.regions.size(); ++r) {
      if (!world.regions[r].area.contains(c.x(), c.y())) continue;
      free_in[r] += 1.0;
      covered_in[r] += covered[cell];
      break;
    }
  }
  const double cell_m2 = cell_m * cell_m;
  coverage.free_m2 = free_cells * cell_m2;
  coverage.share = free_cells > 0 ? covered_cells / free_cells : 0.0;
  for (std::size_t r = 0; r < world.regions.size(); ++r) {
    if (free_in[r] == 0.0) continue;
    coverage.regions.push_back(
        {world.regions[r].name, covered_in[r] / free_in[r], free_in[r] * cell_m2});
  }
  return coverage;
}

}  // namespace omninav::sim
