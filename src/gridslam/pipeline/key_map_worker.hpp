// The thread that integrates key maps into the graph (mapper_internal.hpp, compute.threads >= 2):
// jobs are run one at a time in the order they were pushed. Internal to the Mapper.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

#include "gridslam/pipeline/mapper_internal.hpp"

namespace gridslam::pipeline {

class KeyMapWorker {
 public:
  /// `run` is called on the worker thread for every job, in order. At most `max_queued` jobs
  /// wait (Push blocks beyond: the key maps waiting hold their grids).
  KeyMapWorker(std::function<void(KeyMapJob&)> run, std::size_t max_queued);
  /// Stops after the job in progress; the jobs still queued are dropped.
  ~KeyMapWorker();
  KeyMapWorker(const KeyMapWorker&) = delete;
  KeyMapWorker& operator=(const KeyMapWorker&) = delete;

  void Push(KeyMapJob job);
  /// True while a job is queued or running (a hint: it may change at once).
  [[nodiscard]] bool Busy();
  /// Jobs waiting (not yet started; a hint).
  [[nodiscard]] std::size_t Queued();
  /// Waits until every pushed job has run; rethrows what a job threw.
  void Drain();
  /// CPU time of the worker thread after its latest job [s].
  [[nodiscard]] double CpuSeconds();

 private:
  void Loop();

  std::function<void(KeyMapJob&)> run_;
  std::size_t max_queued_;
  std::mutex mutex_;
  std::condition_variable work_;  ///< A job was pushed, or stop.
  std::condition_variable done_;  ///< A job finished (room in the queue, or idle).
  std::deque<KeyMapJob> queue_;
  bool running_ = false;
  bool stop_ = false;
  std::exception_ptr error_;
  double cpu_seconds_ = 0.0;
  std::thread thread_;
};

}  // namespace gridslam::pipeline
