// Log-odds arithmetic of occupancy grids (Thrun, Burgard, Fox, "Probabilistic Robotics", §9.2):
// a cell stores l = log(p / (1 - p)); independent observations add. The rolling local map (grid/
// rolling_window.hpp) and the key maps store log-odds; images and map_server files use
// probabilities or the nav_msgs/OccupancyGrid convention.
#pragma once

#include <cmath>

namespace gridslam {

/// log(p / (1 - p)); p in (0, 1).
inline double ProbabilityToLogOdds(double p) { return std::log(p / (1.0 - p)); }

/// Value of a cell no scan has touched.
constexpr float kUnknownLogOdds = 0.0F;

}  // namespace gridslam
