// Transactional output folders (issue 17): a command writes everything into a staging folder
// beside its target (`.NAME.tmp-PID`) and commits at the end, so a failed run, a full disk or an
// interrupt leaves either the earlier result or nothing, never a mix; a lock file beside the
// target (`.NAME.lock`, flock) makes a second concurrent run into the same folder refuse.
//
// Commit: a missing target is created by one rename. A target that holds only what an earlier
// gridslam run wrote (the manifest `.gridslam-output` lists it) is swapped whole: renamed aside,
// the staging folder renamed into place, the old one removed. A target that also holds other
// files (the user's) keeps them: each new file is renamed in (atomic per file) and the earlier
// run's files that this run did not write are removed. Stale staging folders of interrupted
// runs are removed by the next run, under the lock.
#pragma once

#include <memory>
#include <string>

#include "gridslam/common/result.hpp"

namespace gridslam::app {

class OutputDir {
 public:
  /// Locks `target` and creates an empty staging folder beside it. RuntimeError (exit 1) if
  /// another run holds the lock or the folder cannot be created.
  static Result<std::unique_ptr<OutputDir>> Begin(const std::string& target);

  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;
  /// Removes the staging folder unless committed; releases the lock.
  ~OutputDir();

  /// The staging folder: write every output file here.
  [[nodiscard]] const std::string& path() const { return staging_; }
  /// The final folder.
  [[nodiscard]] const std::string& target() const { return target_; }

  /// Moves the staged files into the target as described above. RuntimeError on failure.
  [[nodiscard]] Status Commit();

  /// The manifest's name inside an output folder.
  static constexpr const char* kManifest = ".gridslam-output";

 private:
  OutputDir() = default;
  std::string target_;
  std::string staging_;
  std::string lock_path_;
  int lock_fd_ = -1;
  bool committed_ = false;
};

}  // namespace gridslam::app
