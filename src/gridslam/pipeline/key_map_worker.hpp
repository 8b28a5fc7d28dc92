// The thread that integrates key maps into the graph (mapper_internal.hpp, compute.threads >= 2):
// jobs are run one at a time in the order they were pushed. A job's preparation (its
// description, which depends on the key map alone) may instead run on the pushing thread when
// that thread would otherwise wait, or when the worker falls behind (Help). Internal to the
// Mapper.
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
  /// `run` is called on the worker thread for every job, in order. `prepare` runs at most once
  /// per job, on the pushing thread (Push, Help), before `run`; `run` must prepare the jobs that
  /// arrive unprepared. What `prepare` computes must not depend on which thread runs it. At most
  /// `max_queued` jobs wait (Push blocks beyond: the key maps waiting hold their grids).
  KeyMapWorker(std::function<void(KeyMapJob&)> run, std::function<void(KeyMapJob&)> prepare,
               std::size_t max_queued);
  /// Stops after the job in progress; the jobs still queued are dropped.
  ~KeyMapWorker();
  KeyMapWorker(const KeyMapWorker&) = delete;
  KeyMapWorker& operator=(const KeyMapWorker&) = delete;

  /// Queues the job. While the queue is full, prepares waiting jobs instead of sleeping.
  void Push(KeyMapJob job);
  /// Prepares the newest unprepared waiting job when at least `backlog` jobs wait unprepared
  /// (the worker is behind); returns whether it did.
  bool Help(std::size_t backlog);
  /// True while a job is queued or running (a hint: it may change at once).
  [[nodiscard]] bool Busy();
  /// Jobs waiting (not yet started; a hint).
  [[nodiscard]] std::size_t Queued();
  /// Waits until every pushed job has run; rethrows what a job threw.
  void Drain();
  /// CPU time of the worker thread after its latest job [s].
  [[nodiscard]] double CpuSeconds();
  /// Wall time the pushing thread slept in Push, the queue full with nothing to prepare [s].
  [[nodiscard]] double BlockedSeconds();
  /// Wall time the worker waited for a job after its first [s] (the front end was behind).
  [[nodiscard]] double IdleSeconds();

 private:
  enum class Preparation { kWaiting, kRunning, kDone };
  struct Slot {
    KeyMapJob job;
    Preparation preparation = Preparation::kWaiting;
  };

  void Loop();
  /// With the lock held: prepares the newest waiting slot (the lock is released meanwhile; a
  /// deque keeps references to its other elements valid as the worker pops the front); false if
  /// none waits unprepared.
  bool PrepareNewest(std::unique_lock<std::mutex>& lock);

  std::function<void(KeyMapJob&)> run_;
  std::function<void(KeyMapJob&)> prepare_;
  std::size_t max_queued_;
  std::mutex mutex_;
  std::condition_variable work_;  ///< A job was pushed or prepared, or stop.
  std::condition_variable done_;  ///< A job finished (room in the queue, or idle).
  std::deque<Slot> queue_;
  bool running_ = false;
  bool stop_ = false;
  std::exception_ptr error_;
  double cpu_seconds_ = 0.0;
  double blocked_seconds_ = 0.0;
  double idle_seconds_ = 0.0;
  std::thread thread_;
};

}  // namespace gridslam::pipeline
