#include "app_mounting_report.hpp"

#include <cstdio>

namespace gridslam::app {

nlohmann::json MountingJson(const scan_matching::MountingResult& mounting) {
  nlohmann::json j = {{"increments", mounting.increments}, {"measured", mounting.ok}};
  if (mounting.ok) {
    j["offset_m"] = {mounting.offset.x(), mounting.offset.y()};
    j["sigma_m"] = mounting.sigma;
  }
  return j;
}

void PrintMountingNote(const char* command, const std::string& log,
                       const scan_matching::MountingResult& mounting, double cell) {
  const double offset = mounting.offset.norm();
  if (!mounting.ok || offset <= cell || offset <= 3.0 * mounting.sigma) {
    return;
  }
  std::fprintf(stderr,
               "%s: note: %s: the scans put the laser %.3f m ahead, %.3f m left of the mounting "
               "used (+-%.3f m); the trajectory is that of the mounting used. If the log lost its "
               "mounting, give --set log.laser_offset=[x,y,theta]\n",
               command, log.c_str(), mounting.offset.x(), mounting.offset.y(), mounting.sigma);
}

}  // namespace gridslam::app
