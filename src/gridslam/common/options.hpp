// The options convention (docs/style.md §9). Every component keeps its parameters in one plain
// struct with documented defaults and SI units, plus two members:
//
//   template <class V> void Visit(V& v) {
//     v("max_range", max_range, "Readings at or beyond this are no-returns [m]");
//     v.Section("sub", sub_options, "What the sub-component does");
//   }
//   [[nodiscard]] Status Validate() const;
//
// Visit() is the single place that names a struct's keys: the YAML reader, writer and
// `--print-config` (io/options_yaml.hpp) are generic visitors over it, so keys, defaults and their
// documentation cannot drift apart. Field types: bool, int, double, std::string,
// std::vector<double>. Angles in YAML are radians unless the key ends in `_deg`.
#pragma once

#include <string>
#include <vector>

#include "gridslam/common/result.hpp"

namespace gridslam {

/// Validation helper: returns an InvalidInput error naming the option unless `condition` holds.
inline Status Require(bool condition, const std::string& what) {
  if (condition) {
    return Status::Ok();
  }
  return InvalidInput("invalid option: " + what);
}

}  // namespace gridslam
