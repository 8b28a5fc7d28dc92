// The map self-check of `gridslam map` (docs/self_check.md): collects a sample of the scans while
// mapping, replays them at their final poses against the fused map(s), writes map_quality.png
// (map_quality_<c>.png for several map components) and returns report.json's "quality" block.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "gridslam/common/result.hpp"
#include "gridslam/pipeline/mapper.hpp"
#include "gridslam/quality/self_check_options.hpp"

#include "app_image_buffer.hpp"

namespace gridslam::app {

class QualityScans {
 public:
  QualityScans(const quality::SelfCheckOptions& options, int num_robots);
  /// The `index`-th frame of `robot` (0-based, the index of its corrected pose). Keeps the scan
  /// when the odometry moved half the replay spacing since the last kept one (every scan when the
  /// recording has no odometry); the final spacing is applied on the corrected poses.
  void Add(int robot, long index, const Frame& frame);

  struct Kept {
    long index = 0;
    Pose2 T_base_laser;
    LaserScan scan;
  };
  [[nodiscard]] const std::vector<Kept>& Of(int robot) const {
    return kept_[static_cast<std::size_t>(robot)];
  }

 private:
  quality::SelfCheckOptions options_;
  std::vector<std::vector<Kept>> kept_;
  std::vector<std::optional<Pose2>> last_;
};

struct QualityOutcome {
  nlohmann::json report;  ///< report.json "quality".
  std::string summary;    ///< One line for the printed summary.
};

/// Runs the self-check on every map component of `result` and writes the heat images into `dir`
/// (drawn in `pictures`; a buffer of their own when null).
Result<QualityOutcome> RunSelfCheck(const std::string& dir, const pipeline::MapperResult& result,
                                    const QualityScans& scans,
                                    const quality::SelfCheckOptions& options,
                                    const fusion::FusionOptions& fusion, int threads = 1,
                                    ImageBuffer* pictures = nullptr);

}  // namespace gridslam::app
