#include "gridslam/simulation/world.hpp"

#include <cmath>
#include <numbers>

#include "gridslam/simulation/internal/distance_field.hpp"

namespace gridslam::simulation {

bool World::IsWall(const Eigen::Vector2d& p_world) const {
  const Eigen::Array2i cell = walls.Limits().CellIndex(p_world);
  return !walls.Limits().Contains(cell) || walls.at(cell) != 0;
}

double World::Clearance(const Eigen::Vector2d& p_world) const {
  const Eigen::Array2i cell = walls.Limits().CellIndex(p_world);
  if (!walls.Limits().Contains(cell)) {
    return 0.0;
  }
  // Distances are between cell centres: the point lies within half a diagonal of its cell's
  // centre and the wall surface within half a diagonal of the wall cell's centre.
  const double d = static_cast<double>(clearance.at(cell)) - std::numbers::sqrt2 * Resolution();
  return std::max(d, 0.0);
}

World MakeWorld(std::string name, Grid2D<std::uint8_t> walls, std::vector<Eigen::Vector2d> route) {
  GRIDSLAM_CHECK(walls.size() > 0) << "empty world";
  World world;
  world.name = std::move(name);
  const MapLimits& limits = walls.Limits();
  const std::vector<float> cells =
      internal::DistanceTransform(walls.Cells(), limits.Width(), limits.Height());
  world.clearance = Grid2D<float>(limits, 0.0F);
  const auto res = static_cast<float>(limits.Resolution());
  for (std::size_t k = 0; k < cells.size(); ++k) {
    world.clearance.Cells()[k] = cells[k] * res;
  }
  world.walls = std::move(walls);
  world.route = std::move(route);
  return world;
}

World WorldFromGrayImage(std::string name, const Grid2D<std::uint8_t>& image) {
  Grid2D<std::uint8_t> walls(image.Limits(), 0);
  for (std::size_t k = 0; k < image.size(); ++k) {
    walls.Cells()[k] = image.Cells()[k] < 128 ? 1 : 0;
  }
  return MakeWorld(std::move(name), std::move(walls));
}

World WorldFromOccupancy(std::string name, const OccupancyImage& map) {
  Grid2D<std::uint8_t> walls(map.Limits(), 0);
  for (std::size_t k = 0; k < map.size(); ++k) {
    walls.Cells()[k] = map.Cells()[k] == kFreeCell ? 0 : 1;
  }
  return MakeWorld(std::move(name), std::move(walls));
}

OccupancyImage TrueMap(const World& world, double wall_depth) {
  // Distance of each wall cell to free space = distance transform of the free cells.
  const MapLimits& limits = world.walls.Limits();
  std::vector<std::uint8_t> free(world.walls.size());
  for (std::size_t k = 0; k < free.size(); ++k) {
    free[k] = world.walls.Cells()[k] == 0 ? 1 : 0;
  }
  const std::vector<float> to_free =
      internal::DistanceTransform(free, limits.Width(), limits.Height());
  OccupancyImage map(limits, kUnknownCell);
  const double depth_cells = wall_depth / limits.Resolution();
  for (std::size_t k = 0; k < free.size(); ++k) {
    if (free[k] != 0) {
      map.Cells()[k] = kFreeCell;
    } else if (to_free[k] <= depth_cells) {
      map.Cells()[k] = kOccupiedCell;
    }
  }
  return map;
}

WorldBuilder::WorldBuilder(double width, double height, double resolution) {
  GRIDSLAM_CHECK(width > 0.0 && height > 0.0 && resolution > 0.0)
      << width << " x " << height << " at " << resolution;
  const MapLimits limits(resolution, Eigen::Vector2d::Zero(),
                         static_cast<int>(std::ceil(width / resolution - 1e-9)),
                         static_cast<int>(std::ceil(height / resolution - 1e-9)));
  walls_ = Grid2D<std::uint8_t>(limits, 1);
}

WorldBuilder& WorldBuilder::Carve(double x0, double y0, double x1, double y1) {
  Set(x0, y0, x1, y1, 0);
  return *this;
}

WorldBuilder& WorldBuilder::Fill(double x0, double y0, double x1, double y1) {
  Set(x0, y0, x1, y1, 1);
  return *this;
}

void WorldBuilder::Set(double x0, double y0, double x1, double y1, std::uint8_t value) {
  const MapLimits& limits = walls_.Limits();
  const double res = limits.Resolution();
  // Cell i is covered when its centre (i + 0.5) * res lies in [x0, x1).
  auto first = [&](double v, double origin) {
    return static_cast<int>(std::ceil((v - origin) / res - 0.5 - 1e-9));
  };
  const int i0 = std::max(first(x0, limits.Origin().x()), 0);
  const int i1 = std::min(first(x1, limits.Origin().x()), limits.Width());
  const int j0 = std::max(first(y0, limits.Origin().y()), 0);
  const int j1 = std::min(first(y1, limits.Origin().y()), limits.Height());
  for (int j = j0; j < j1; ++j) {
    for (int i = i0; i < i1; ++i) {
      walls_(i, j) = value;
    }
  }
}

World WorldBuilder::Build(std::string name, std::vector<Eigen::Vector2d> route) const {
  return MakeWorld(std::move(name), walls_, std::move(route));
}

}  // namespace gridslam::simulation
