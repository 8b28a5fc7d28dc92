// Writing an output file all or nothing: the text goes to a temporary file beside the target,
// which is renamed over it only once everything was written and flushed, so a failed command
// never leaves a half-written file (docs/design.md §2).
#pragma once

#include <cstdio>
#include <functional>
#include <string>

#include "gridslam/common/result.hpp"

namespace gridslam::io {

/// Writes `contents` to `path` through a temporary file and a rename. RuntimeError (exit 1) if
/// the folder is not writable or the disk is full.
Status WriteFileAtomically(const std::string& path, const std::string& contents);

/// Writes the contents into an open file; false when a write failed.
using FileWriter = std::function<bool(std::FILE*)>;
/// The same with the contents written piece by piece by `write` (a large file need not be held
/// in memory first).
Status WriteFileAtomically(const std::string& path, const FileWriter& write);

}  // namespace gridslam::io
