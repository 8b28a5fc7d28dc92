// The simulated world: a 2D grid of wall and free cells (Grid2D, origin at the lower-left
// corner as map_server's), its clearance field (distance to the nearest wall, from an exact
// Euclidean distance transform) and optionally a built-in route. Worlds come from the built-in
// generators (`office`, `ambiguous`, `campus`, `corridors`; builtin_worlds.cpp), from a floor-plan
// image (dark = wall) or from an occupancy map; WorldBuilder draws new ones from free and solid
// rectangles.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "gridslam/common/result.hpp"
#include "gridslam/grid/grid2d.hpp"

namespace gridslam::simulation {

struct World {
  std::string name;
  Grid2D<std::uint8_t> walls;  ///< 1 = wall (rays stop, robots collide), 0 = free.
  Grid2D<float> clearance;     ///< Distance from each cell centre to the nearest wall cell [m].
  std::vector<Eigen::Vector2d> route;  ///< Built-in tour (world frame, closed), may be empty.

  [[nodiscard]] double Resolution() const { return walls.Limits().Resolution(); }
  /// True for wall cells and for points outside the grid.
  [[nodiscard]] bool IsWall(const Eigen::Vector2d& p_world) const;
  /// Distance from `p_world` to the nearest wall surface (approximate to half a cell, never an
  /// overestimate); 0 outside the grid or inside walls [m].
  [[nodiscard]] double Clearance(const Eigen::Vector2d& p_world) const;
};

/// Builds a World from its wall grid: computes the clearance field. `walls` must be non-empty.
World MakeWorld(std::string name, Grid2D<std::uint8_t> walls,
                std::vector<Eigen::Vector2d> route = {});

/// A world from a grayscale floor plan (values 0..255, e.g. a PNG read into a grid with row 0
/// at the bottom): pixels darker than 128 are walls.
World WorldFromGrayImage(std::string name, const Grid2D<std::uint8_t>& image);

/// A world from an occupancy map (map_server): occupied and unknown cells are walls.
World WorldFromOccupancy(std::string name, const OccupancyImage& map);

/// The true map of a world for map_server: free cells 0, wall cells within `wall_depth` of free
/// space 100, deeper wall cells (the solid outside of the building) unknown.
OccupancyImage TrueMap(const World& world, double wall_depth = 0.3);

/// Draws worlds from axis-aligned rectangles in metres; a rectangle covers the cells whose
/// centres lie inside it. The world starts solid; rooms and corridors are carved out.
class WorldBuilder {
 public:
  /// A `width` x `height` [m] world with its lower-left corner at (0, 0), all wall.
  WorldBuilder(double width, double height, double resolution);
  /// Makes [x0, x1) x [y0, y1) free.
  WorldBuilder& Carve(double x0, double y0, double x1, double y1);
  /// Makes [x0, x1) x [y0, y1) wall (furniture, pillars).
  WorldBuilder& Fill(double x0, double y0, double x1, double y1);
  [[nodiscard]] World Build(std::string name, std::vector<Eigen::Vector2d> route) const;

 private:
  void Set(double x0, double y0, double x1, double y1, std::uint8_t value);
  Grid2D<std::uint8_t> walls_;
};

/// Names of the built-in worlds ("office", "ambiguous", "campus", "corridors", "courts").
std::vector<std::string> BuiltinWorldNames();

/// A built-in world at the given resolution [m], with its tour; InvalidInput for unknown names.
/// `layout` (>= 1) draws the rooms of a world laid out at random ("courts"); the others ignore it.
Result<World> MakeBuiltinWorld(const std::string& name, double resolution, int layout = 1);

}  // namespace gridslam::simulation
