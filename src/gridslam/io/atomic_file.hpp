// Writing an output file all or nothing: the text goes to a temporary file beside the target,
// which is renamed over it only once everything was written and flushed, so a failed command
// never leaves a half-written file (docs/design.md §2).
#pragma once

#include <string>

#include "gridslam/common/result.hpp"

namespace gridslam::io {

/// Writes `contents` to `path` through a temporary file and a rename. RuntimeError (exit 1) if
/// the folder is not writable or the disk is full.
Status WriteFileAtomically(const std::string& path, const std::string& contents);

}  // namespace gridslam::io
