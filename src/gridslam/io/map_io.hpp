// ROS map_server maps (docs/formats.md §5): a YAML file (image, resolution, origin, negate,
// occupied_thresh, free_thresh, mode) beside an image. Written exactly as map_saver writes them:
// trinary values 254 free / 0 occupied / 205 unknown (free when 0 <= v <= 25, occupied when
// v >= 65), `negate: 0`, `occupied_thresh: 0.65`, `free_thresh: 0.196`, binary PGM (P5) or PNG.
// Read as map_server's image_loader reads them: p = (255 - mean of the colour channels) / 255
// (x / 255 with negate), trinary/scale/raw modes with strict comparisons (ROS 1). Image row 0 is
// the top of the map and OccupancyImage row 0 the bottom: rows are flipped both ways. PGM (P5,
// P2) is parsed here; other image formats (PNG) go through OpenCV's imgcodecs.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "gridslam/common/result.hpp"
#include "gridslam/grid/grid2d.hpp"

namespace gridslam::io {

/// map_saver's trinary pixel value of an occupancy value: 254 free, 0 occupied, 205 unknown.
std::uint8_t TrinaryPixel(signed char occupancy);

/// Writes `map` as `yaml_path` plus an image named `image_name` (relative to the YAML's folder;
/// ".pgm" gives binary PGM, ".png" PNG). The YAML's origin is the map's lower-left corner.
Status WriteMap(const std::string& yaml_path, const std::string& image_name,
                const OccupancyImage& map);

/// Reads a map_server YAML and its image. InvalidInput for malformed YAML or image, NotFound if
/// a file is missing. A rotated origin (yaw != 0) is rejected.
Result<OccupancyImage> ReadMap(const std::string& yaml_path);

/// Writes the map's trinary image alone (PGM or PNG by extension), top row first.
Status WriteMapImage(const std::string& path, const OccupancyImage& map);

/// Writes an 8-bit grayscale image (PGM or PNG by extension) of a grid, top row first.
Status WriteGrayImage(const std::string& path, const Grid2D<std::uint8_t>& image);

/// A picture for people (PNG by extension): the map's trinary image with `paths` (world frame,
/// metres) drawn over it, one colour each (red, blue, green, orange, ...), a dot at each start.
Status WriteMapPicture(const std::string& path, const OccupancyImage& map,
                       const std::vector<std::vector<Eigen::Vector2d>>& paths);

/// Reads an image (PGM, PNG or anything OpenCV reads) as 8-bit gray (mean of the colour
/// channels), row 0 at the bottom, with the given cell size and lower-left corner.
Result<Grid2D<std::uint8_t>> ReadGrayImage(const std::string& path, double resolution,
                                           const Eigen::Vector2d& origin = Eigen::Vector2d::Zero());

}  // namespace gridslam::io
