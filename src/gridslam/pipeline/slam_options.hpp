// SlamOptions: the whole configuration, one section per component (docs/style.md §9; KISS-ICP's
// KISSConfig, Cartographer's TrajectoryBuilderOptions). config/default.yaml mirrors it and
// `gridslam --print-config` prints it. Each component's struct lives in its module's header; add
// a section here when a component lands.
#pragma once

#include "gridslam/benchmark/align_eval_options.hpp"
#include "gridslam/common/options.hpp"
#include "gridslam/description/description_options.hpp"
#include "gridslam/eval/eval_options.hpp"
#include "gridslam/fusion/global_grid.hpp"
#include "gridslam/io/carmen_options.hpp"
#include "gridslam/loop_closure/loop_closure_options.hpp"
#include "gridslam/matching/align.hpp"
#include "gridslam/multi_robot/log_split.hpp"
#include "gridslam/pipeline/mapper_options.hpp"
#include "gridslam/pose_graph/optimizer.hpp"
#include "gridslam/quality/self_check_options.hpp"
#include "gridslam/scan_matching/front_end_options.hpp"
#include "gridslam/simulation/simulation_options.hpp"

namespace gridslam {

struct SlamOptions {
  io::CarmenOptions log;                        ///< Reading CARMEN logs.
  scan_matching::FrontEndOptions front_end;     ///< Scan matching, local map, key maps.
  description::DescriptionOptions description;  ///< Key-map description (DT + SURF).
  matching::AlignOptions matching;         ///< Key-map alignment (matching, RANSAC, verification).
  eval::EvalOptions eval;                  ///< Benchmark relation metric.
  pose_graph::OptimizerOptions optimizer;  ///< Pose-graph optimization.
  loop_closure::LoopClosureOptions loop_closure;  ///< Loop-closure search and gates.
  pipeline::GraphOptions graph;                   ///< Building and optimizing the key-map graph.
  fusion::FusionOptions fusion;                   ///< Global map fusion.
  pipeline::ComputeOptions compute;               ///< Threads and memory of the mapper.
  quality::SelfCheckOptions quality;              ///< Map self-check (docs/self_check.md).
  simulation::SimulationOptions simulation;       ///< `gridslam simulate`.
  benchmark::AlignEvalOptions align_eval;         ///< `gridslam align-eval` (docs/design.md §3.2).
  multi_robot::SplitOptions split;                ///< `gridslam split` (one log as several robots).

  template <class V>
  void Visit(V& v) {
    v.Section("log", log, "Reading CARMEN laser logs (docs/formats.md §1)");
    v.Section("front_end", front_end,
              "Front end: local map, scan matching, key maps (docs/design.md §1.2-1.3)");
    v.Section("description", description,
              "Key-map description: distance transform + SURF (docs/design.md §1.4)");
    v.Section("matching", matching, "Key-map alignment without prior (docs/design.md §1.5)");
    v.Section("eval", eval, "Benchmark relation metric (docs/design.md §3.1)");
    v.Section("optimizer", optimizer, "Pose-graph optimization (docs/design.md §1.7)");
    v.Section("loop_closure", loop_closure, "Loop-closure search and gates (docs/design.md §1.6)");
    v.Section("graph", graph, "Key-map graph: edges, online and final optimization");
    v.Section("fusion", fusion, "Global map fusion (docs/design.md §1.8)");
    v.Section("compute", compute, "Threads and memory of the mapper (docs/speed.md)");
    v.Section("quality", quality, "Map self-check without ground truth (docs/self_check.md)");
    v.Section("simulation", simulation, "The built-in laser simulator (gridslam simulate)");
    v.Section("align_eval", align_eval, "Key-map alignment benchmark (gridslam align-eval)");
    v.Section("split", split, "Cutting one log into several robots (gridslam split)");
  }
  /// The sections the mapper uses (pipeline::Mapper takes only these).
  [[nodiscard]] pipeline::MapperOptions Mapper() const {
    return {front_end, description, matching, optimizer, loop_closure, graph, fusion, compute};
  }
  [[nodiscard]] Status Validate() const {
    GRIDSLAM_RETURN_IF_ERROR(log.Validate());
    GRIDSLAM_RETURN_IF_ERROR(front_end.Validate());
    GRIDSLAM_RETURN_IF_ERROR(description.Validate());
    GRIDSLAM_RETURN_IF_ERROR(matching.Validate());
    GRIDSLAM_RETURN_IF_ERROR(eval.Validate());
    GRIDSLAM_RETURN_IF_ERROR(optimizer.Validate());
    GRIDSLAM_RETURN_IF_ERROR(loop_closure.Validate());
    GRIDSLAM_RETURN_IF_ERROR(graph.Validate());
    GRIDSLAM_RETURN_IF_ERROR(fusion.Validate());
    GRIDSLAM_RETURN_IF_ERROR(compute.Validate());
    GRIDSLAM_RETURN_IF_ERROR(quality.Validate());
    GRIDSLAM_RETURN_IF_ERROR(simulation.Validate());
    GRIDSLAM_RETURN_IF_ERROR(align_eval.Validate());
    GRIDSLAM_RETURN_IF_ERROR(split.Validate());
    return Status::Ok();
  }
};

}  // namespace gridslam
