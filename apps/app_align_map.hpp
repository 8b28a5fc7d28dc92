// `gridslam map --align-map`: the map frame rotated so that the building's dominant wall
// directions lie along its axes. By default the map frame is the first key map's frame (the
// robot's first odometry axes), so maps of rectangular buildings come out tilted.
#pragma once

#include "gridslam/grid/grid2d.hpp"
#include "gridslam/grid/tiled_grid.hpp"
#include "gridslam/pipeline/mapper.hpp"

namespace gridslam::app {

/// Angle in [-pi/4, pi/4) of the dominant wall directions of a log-odds map (walls at it and at
/// it + 90 degrees): the rotation whose axes collect the obstacle cells into the sharpest
/// projections (fewest, fullest rows and columns), searched in 1 degree and then 0.05 degree
/// steps. Unlike edge-gradient histograms, it is not pulled towards 45 degrees by the staircase
/// of rasterized walls. 0 if the map has (almost) no obstacles. Cells with log-odds above
/// `occupied_log_odds` are obstacles.
double DominantWallAngle(const TiledGrid<float>& log_odds, float occupied_log_odds);

/// Rotates map component `component`'s frame by -angle (about its origin): the trajectories of
/// its robots, its pose-graph vertices and its fused grid (resampled, nearest cell, onto a grid
/// covering the rotated map's observed cells plus `margin` [m]). Relative quantities (edges,
/// closures) are unchanged.
void RotateMapFrame(pipeline::MapperResult& result, int component, double angle, double margin);

}  // namespace gridslam::app
