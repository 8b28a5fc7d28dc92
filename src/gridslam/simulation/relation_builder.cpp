#include "gridslam/simulation/relation_builder.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace gridslam::simulation {
namespace {

const Pose2& Truth(const Frame& frame) {
  GRIDSLAM_CHECK(frame.T_world_base_true.has_value()) << "frame without ground truth";
  return *frame.T_world_base_true;
}

eval::Relation MakeRelation(const Frame& a, const Frame& b) {
  return {a.time, b.time, Between(Truth(a), Truth(b))};
}

/// Index of the frame in `candidates` nearest to `truth` within the limits and in line of sight,
/// or -1. Only indices in [begin, end) are considered.
long Nearest(const Pose2& truth, const std::vector<Frame>& candidates, std::size_t begin,
             std::size_t end, const RelationSimOptions& options, const RayCaster& caster) {
  std::vector<std::pair<double, std::size_t>> near;
  const double max_sq = options.revisit_max_distance * options.revisit_max_distance;
  for (std::size_t j = begin; j < end; ++j) {
    const Pose2& other = Truth(candidates[j]);
    const double d_sq = (other.translation() - truth.translation()).squaredNorm();
    if (d_sq <= max_sq &&
        std::abs(NormalizeAngle(other.theta() - truth.theta())) <= options.revisit_max_angle) {
      near.emplace_back(d_sq, j);
    }
  }
  std::sort(near.begin(), near.end());
  for (const auto& [d_sq, j] : near) {
    if (caster.LineOfSight(truth.translation(), Truth(candidates[j]).translation())) {
      return static_cast<long>(j);
    }
  }
  return -1;
}

void SortRelations(std::vector<eval::Relation>& relations) {
  std::sort(relations.begin(), relations.end(),
            [](const auto& a, const auto& b) { return a.t1 != b.t1 ? a.t1 < b.t1 : a.t2 < b.t2; });
}

}  // namespace

std::vector<eval::Relation> MakeWithinRelations(const std::vector<Frame>& frames,
                                                const RelationSimOptions& options,
                                                const RayCaster& caster) {
  std::vector<eval::Relation> relations;
  const std::size_t n = frames.size();
  const Duration span = SecondsToDuration(options.short_span);
  const auto short_stride = static_cast<std::size_t>(options.short_stride);
  for (std::size_t i = 0; i < n; i += short_stride) {
    std::size_t j = i + 1;
    while (j < n && frames[j].time - frames[i].time < span) {
      ++j;
    }
    if (j < n) {
      relations.push_back(MakeRelation(frames[i], frames[j]));
    }
  }
  const Duration gap = SecondsToDuration(options.revisit_min_gap);
  const auto revisit_stride = static_cast<std::size_t>(options.revisit_stride);
  std::size_t end = 0;  // frames[0, end) are at least `gap` older than frames[i]
  for (std::size_t i = 0; i < n; i += revisit_stride) {
    while (end < i && frames[i].time - frames[end].time >= gap) {
      ++end;
    }
    const long j = Nearest(Truth(frames[i]), frames, 0, end, options, caster);
    if (j >= 0) {
      relations.push_back(MakeRelation(frames[static_cast<std::size_t>(j)], frames[i]));
    }
  }
  SortRelations(relations);
  return relations;
}

std::vector<eval::Relation> MakeBetweenRelations(const std::vector<RobotRun>& robots,
                                                 const RelationSimOptions& options,
                                                 const RayCaster& caster) {
  std::vector<eval::Relation> relations;
  const auto stride = static_cast<std::size_t>(options.between_stride);
  for (std::size_t a = 0; a < robots.size(); ++a) {
    for (std::size_t b = a + 1; b < robots.size(); ++b) {
      const std::vector<Frame>& fa = robots[a].frames;
      const std::vector<Frame>& fb = robots[b].frames;
      for (std::size_t i = 0; i < fa.size(); i += stride) {
        const long j = Nearest(Truth(fa[i]), fb, 0, fb.size(), options, caster);
        if (j >= 0) {
          relations.push_back(MakeRelation(fa[i], fb[static_cast<std::size_t>(j)]));
        }
      }
    }
  }
  SortRelations(relations);
  return relations;
}

}  // namespace gridslam::simulation
