#include "gridslam/pipeline/key_map_worker.hpp"

#include <ctime>
#include <utility>

namespace gridslam::pipeline {

KeyMapWorker::KeyMapWorker(std::function<void(KeyMapJob&)> run, std::size_t max_queued)
    : run_(std::move(run)), max_queued_(max_queued < 1 ? 1 : max_queued) {
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

void KeyMapWorker::Push(KeyMapJob job) {
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [&] { return queue_.size() < max_queued_ || error_ != nullptr; });
  queue_.push_back(std::move(job));
  lock.unlock();
  work_.notify_one();
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

void KeyMapWorker::Loop() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    work_.wait(lock, [&] { return stop_ || (!queue_.empty() && error_ == nullptr); });
    if (stop_) {
      return;
    }
    KeyMapJob job = std::move(queue_.front());
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
