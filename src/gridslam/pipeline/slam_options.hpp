// SlamOptions: the whole configuration, one section per component (STYLE.md §9; KISS-ICP's
// KISSConfig, Cartographer's TrajectoryBuilderOptions). config/default.yaml mirrors it and
// `gridslam --print-config` prints it. Each component's struct lives in its module's header; add
// a section here when a component lands.
#pragma once

#include "gridslam/common/options.hpp"
#include "gridslam/io/carmen_options.hpp"

namespace gridslam {

struct SlamOptions {
  io::CarmenOptions log;  ///< Reading CARMEN logs.

  template <class V>
  void Visit(V& v) {
    v.Section("log", log, "Reading CARMEN laser logs (FORMATS.md section 1)");
  }
  [[nodiscard]] Status Validate() const {
    GRIDSLAM_RETURN_IF_ERROR(log.Validate());
    return Status::Ok();
  }
};

}  // namespace gridslam
