// The pictures `gridslam map` draws for people (docs/guide.md §2): map.png, the map with metric
// axes and a scale bar, and map_graph.png, the same with each robot's trajectory, the key maps
// and the accepted loop closures, and a legend. map.pgm (map_server's input) stays unannotated.
#pragma once

#include <string>

#include "gridslam/common/result.hpp"
#include "gridslam/grid/grid2d.hpp"
#include "gridslam/pipeline/mapper.hpp"

#include "app_image_buffer.hpp"

namespace gridslam::app {

/// Colour of robot `r`'s trajectory in map_graph.png, as BGR (none of them is the closures'
/// green or the key maps' colour).
struct Bgr {
  int b, g, r;
};
Bgr RobotColour(std::size_t robot);

/// Tick spacing for an axis `length_m` long: 1, 2 or 5 times a power of ten, about 4-10 ticks.
double TickSpacing(double length_m);

/// map.png: the occupancy map (free white, occupied black, unknown grey) with axes in metres of
/// the map frame along the left and bottom edges and a scale bar; an 8-bit grey PNG, drawn in
/// `pictures`, compressed by up to `threads` threads.
Status WriteMapPicture(const std::string& path, const OccupancyImage& map, ImageBuffer& pictures,
                       int threads = 1);

/// map_graph.png: map.png's picture plus the trajectories of the robots of map `component`, the
/// key maps, the accepted loop closures and a legend naming each.
Status WriteGraphPicture(const std::string& path, const OccupancyImage& map,
                         const pipeline::MapperResult& result, int component, ImageBuffer& pictures,
                         int threads = 1);

}  // namespace gridslam::app
