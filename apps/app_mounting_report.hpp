// The laser's mounting as the scans measure it (scan_matching/mounting_estimate.hpp;
// docs/frames.md): its report.json block and the note `map` and `track` print when it is clearly
// off.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "gridslam/scan_matching/mounting_estimate.hpp"

namespace gridslam::app {

/// {"increments", "measured"} and, when measured, "offset_m" [ahead, left] and "sigma_m" (either
/// component).
nlohmann::json MountingJson(const scan_matching::MountingResult& mounting);

/// Prints a note to stderr when the measured offset exceeds both `cell` [m] (a map cell: less
/// moves no wall) and 3 standard deviations. `command` prefixes the line ("gridslam map").
void PrintMountingNote(const char* command, const std::string& log,
                       const scan_matching::MountingResult& mounting, double cell);

}  // namespace gridslam::app
