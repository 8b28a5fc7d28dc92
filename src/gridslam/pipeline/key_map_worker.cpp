#include "gridslam/pipeline/key_map_worker.hpp"

#include <chrono>
#include <ctime>
#include <utility>

namespace gridslam::pipeline {

KeyMapWorker::KeyMapWorker(std::function<void(KeyMapJob&)> run,
                           std::function<void(KeyMapJob&)> prepare, std::size_t max_queued)
    : run_(std::move(run)),
      prepare_(std::move(prepare)),
      max_queued_(max_queued < 1 ? 1 : max_queued) {
  thread_ = std::thread([this] { Loop(); });
}

KeyMapWorker::~KeyMapWorker() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  work_.notify_all();
  thread_.join();
}

bool KeyMapWorker::PrepareNewest(std::unique_lock<std::mutex>& lock) {
  for (auto it = queue_.rbegin(); it != queue_.rend(); ++it) {
    if (it->preparation != Preparation::kWaiting) {
      continue;
    }
    Slot& slot = *it;
    slot.preparation = Preparation::kRunning;  // the worker does not pop it meanwhile
    lock.unlock();
    std::exception_ptr error;
    try {
      prepare_(slot.job);
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    slot.preparation = Preparation::kDone;
    error_ = error != nullptr && error_ == nullptr ? error : error_;
    work_.notify_all();
    done_.notify_all();
    return true;
  }
  return false;
}

void KeyMapWorker::Push(KeyMapJob job) {
  std::unique_lock<std::mutex> lock(mutex_);
  while (queue_.size() >= max_queued_ && error_ == nullptr) {
    if (!PrepareNewest(lock)) {
      const auto start = std::chrono::steady_clock::now();
      done_.wait(lock);
      blocked_seconds_ += SecondsSince(start);
    }
  }
  queue_.push_back({std::move(job), Preparation::kWaiting});
  lock.unlock();
  work_.notify_one();
}

bool KeyMapWorker::Help(std::size_t backlog) {
  std::unique_lock<std::mutex> lock(mutex_);
  std::size_t waiting = 0;
  for (const Slot& slot : queue_) {
    waiting += slot.preparation == Preparation::kWaiting ? 1 : 0;
  }
  return waiting >= backlog && error_ == nullptr && PrepareNewest(lock);
}

bool KeyMapWorker::Busy() {
  const std::lock_guard<std::mutex> lock(mutex_);
  return running_ || !queue_.empty();
}

std::size_t KeyMapWorker::Queued() {
  const std::lock_guard<std::mutex> lock(mutex_);
  return queue_.size();
}

void KeyMapWorker::Drain() {
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [&] { return (!running_ && queue_.empty()) || error_ != nullptr; });
  if (error_ != nullptr) {
    std::rethrow_exception(error_);
  }
}

double KeyMapWorker::CpuSeconds() {
  const std::lock_guard<std::mutex> lock(mutex_);
  return cpu_seconds_;
}

double KeyMapWorker::BlockedSeconds() {
  const std::lock_guard<std::mutex> lock(mutex_);
  return blocked_seconds_;
}

double KeyMapWorker::IdleSeconds() {
  const std::lock_guard<std::mutex> lock(mutex_);
  return idle_seconds_;
}

void KeyMapWorker::Loop() {
  std::unique_lock<std::mutex> lock(mutex_);
  bool first = true;
  while (true) {
    // The front job, once no other thread is preparing it.
    const auto start = std::chrono::steady_clock::now();
    work_.wait(lock, [&] {
      return stop_ || (!queue_.empty() && error_ == nullptr &&
                       queue_.front().preparation != Preparation::kRunning);
    });
    if (stop_) {
      return;
    }
    idle_seconds_ += first ? 0.0 : SecondsSince(start);
    first = false;
    KeyMapJob job = std::move(queue_.front().job);
    queue_.pop_front();
    running_ = true;
    lock.unlock();
    std::exception_ptr error;
    try {
      run_(job);
    } catch (...) {
      error = std::current_exception();
    }
    timespec cpu{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &cpu);
    lock.lock();
    cpu_seconds_ = static_cast<double>(cpu.tv_sec) + 1e-9 * static_cast<double>(cpu.tv_nsec);
    running_ = false;
    error_ = error != nullptr ? error : error_;
    done_.notify_all();
  }
}

}  // namespace gridslam::pipeline
