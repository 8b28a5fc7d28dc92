#include "app_output_dir.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <vector>

#include "gridslam/io/atomic_file.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

namespace gridslam::app {
namespace fs = std::filesystem;

namespace {

/// The file names listed in a folder's manifest (empty if it has none).
std::set<std::string> ReadManifest(const fs::path& dir) {
  std::set<std::string> names;
  std::ifstream in(dir / OutputDir::kManifest);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.front() != '#') {
      names.insert(line);
    }
  }
  return names;
}

}  // namespace

Result<std::unique_ptr<OutputDir>> OutputDir::Begin(const std::string& target) {
  std::unique_ptr<OutputDir> out(new OutputDir());
  fs::path path = fs::path(target).lexically_normal();
  if (path.filename().empty()) {
    path = path.parent_path();  // "dir/" -> "dir"
  }
  const std::string name = path.filename().string();
  if (name.empty() || name == "." || name == "..") {
    return InvalidInput("output folder '" + target +
                        "': name a folder of its own (not '.', '..' or '/')");
  }
  const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) {
    return RuntimeError("cannot create " + parent.string() + ": " + ec.message());
  }
  if (fs::exists(path) && !fs::is_directory(path)) {
    return InvalidInput("output '" + target + "' exists and is not a folder");
  }
  out->target_ = path.string();
  out->lock_path_ = (parent / ("." + name + ".lock")).string();
  out->lock_fd_ = ::open(out->lock_path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (out->lock_fd_ < 0) {
    return RuntimeError("cannot create the lock file " + out->lock_path_);
  }
  if (::flock(out->lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    return RuntimeError("another gridslam run is writing into " + target + " (it holds " +
                        out->lock_path_ + "); wait for it or choose another folder");
  }
  // Leftovers of interrupted runs (only runs holding the lock create them).
  const std::string tmp_prefix = "." + name + ".tmp-";
  const std::string old_prefix = "." + name + ".old-";
  for (const auto& entry : fs::directory_iterator(parent, ec)) {
    const std::string n = entry.path().filename().string();
    if (n.rfind(tmp_prefix, 0) == 0 || n.rfind(old_prefix, 0) == 0) {
      fs::remove_all(entry.path(), ec);
    }
  }
  out->staging_ = (parent / (tmp_prefix + std::to_string(::getpid()))).string();
  fs::create_directory(out->staging_, ec);
  if (ec) {
    return RuntimeError("cannot create " + out->staging_ + ": " + ec.message());
  }
  return out;
}

OutputDir::~OutputDir() {
  std::error_code ec;
  if (!committed_ && !staging_.empty()) {
    fs::remove_all(staging_, ec);
  }
  if (lock_fd_ >= 0) {
    ::close(lock_fd_);  // releases the flock; the (empty) lock file stays for the next run
  }
}

Status OutputDir::Commit() {
  std::error_code ec;
  const fs::path staging(staging_);
  const fs::path target(target_);
  // The manifest: every file this run wrote.
  std::vector<std::string> written;
  for (const auto& entry : fs::directory_iterator(staging, ec)) {
    written.push_back(entry.path().filename().string());
  }
  if (ec) {
    return RuntimeError("cannot list " + staging_ + ": " + ec.message());
  }
  std::sort(written.begin(), written.end());
  std::string manifest = "# files written by the gridslam run that wrote this folder\n";
  for (const std::string& n : written) {
    manifest += n + "\n";
  }
  GRIDSLAM_RETURN_IF_ERROR(io::WriteFileAtomically((staging / kManifest).string(), manifest));

  if (!fs::exists(target)) {
    fs::rename(staging, target, ec);
    if (ec) {
      return RuntimeError("cannot rename " + staging_ + " to " + target_ + ": " + ec.message());
    }
    committed_ = true;
    return Status::Ok();
  }
  const std::set<std::string> earlier = ReadManifest(target);
  bool only_ours = true;
  for (const auto& entry : fs::directory_iterator(target, ec)) {
    const std::string n = entry.path().filename().string();
    if (n != kManifest && earlier.count(n) == 0) {
      only_ours = false;
      break;
    }
  }
  if (only_ours) {
    // Swap the whole folder: the old result until the first rename, the new after the second.
    std::string old_name = ".";
    old_name += target.filename().string();
    old_name += ".old-";
    old_name += std::to_string(::getpid());
    const fs::path old =
        (target.has_parent_path() ? target.parent_path() : fs::path(".")) / old_name;
    fs::rename(target, old, ec);
    if (ec) {
      return RuntimeError("cannot move the earlier result " + target_ + " aside: " + ec.message());
    }
    fs::rename(staging, target, ec);
    if (ec) {
      std::error_code ignored;
      fs::rename(old, target, ignored);  // put the earlier result back
      return RuntimeError("cannot rename " + staging_ + " to " + target_ + ": " + ec.message());
    }
    committed_ = true;
    fs::remove_all(old, ec);
    return Status::Ok();
  }
  // The folder holds other files too: move ours in one by one, drop the earlier run's others.
  for (const std::string& n : written) {
    fs::rename(staging / n, target / n, ec);
    if (ec) {
      return RuntimeError("cannot move " + (staging / n).string() + " into " + target_ + ": " +
                          ec.message());
    }
  }
  for (const std::string& n : earlier) {
    if (!std::binary_search(written.begin(), written.end(), n) && n != kManifest &&
        n.find('/') == std::string::npos && n != "." && n != "..") {
      fs::remove_all(target / n, ec);
    }
  }
  fs::rename(staging / kManifest, target / kManifest, ec);
  committed_ = true;
  fs::remove_all(staging, ec);
  return Status::Ok();
}

}  // namespace gridslam::app
