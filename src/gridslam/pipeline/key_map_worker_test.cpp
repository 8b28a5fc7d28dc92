#include "gridslam/pipeline/key_map_worker.hpp"

#include <atomic>
#include <chrono>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace gridslam::pipeline {
namespace {

// Jobs whose preparation marks them (an empty description): `run` records the order and
// whether each arrived prepared.
struct Recorder {
  std::mutex mutex;
  std::vector<int> order;
  std::vector<bool> arrived_prepared;
  std::atomic<int> prepared_by_worker{0};
};

KeyMapJob Job(int id) {
  KeyMapJob job;
  job.id = id;
  return job;
}

TEST(KeyMapWorker, RunsEveryJobOnceInOrderPreparedByOneThreadOrTheOther) {
  Recorder recorder;
  std::atomic<bool> release{false};
  KeyMapWorker worker(
      [&](KeyMapJob& job) {
        while (!release) {  // the first job holds the worker: the others queue up
          std::this_thread::yield();
        }
        const bool prepared = job.described.has_value();
        if (!prepared) {
          job.described = DescribedKeyMap{};
          ++recorder.prepared_by_worker;
        }
        const std::lock_guard<std::mutex> lock(recorder.mutex);
        recorder.order.push_back(job.id);
        recorder.arrived_prepared.push_back(prepared);
      },
      [](KeyMapJob& job) {
        ASSERT_FALSE(job.described.has_value()) << "prepared twice";
        job.described = DescribedKeyMap{};
      },
      3);
  worker.Push(Job(0));
  worker.Push(Job(1));
  worker.Push(Job(2));
  // The worker holds job 0 or has not taken it yet: at least two wait unprepared.
  EXPECT_TRUE(worker.Help(2));
  // Job 2, the newest, is prepared: only job 1 (and 0, unless the worker took it) still waits
  // unprepared.
  EXPECT_FALSE(worker.Help(3));
  release = true;
  for (int id = 3; id < 40; ++id) {
    worker.Push(Job(id));
    worker.Help(1);
  }
  worker.Drain();
  ASSERT_EQ(recorder.order.size(), 40U);
  for (int id = 0; id < 40; ++id) {
    EXPECT_EQ(recorder.order[static_cast<std::size_t>(id)], id);
  }
  EXPECT_TRUE(recorder.arrived_prepared[2]);
}

TEST(KeyMapWorker, AFullQueuePreparesWaitingJobsInsteadOfSleeping) {
  std::atomic<bool> started{false};
  std::atomic<bool> release{false};
  std::atomic<int> prepared{0};
  std::vector<bool> arrived_prepared;
  KeyMapWorker worker(
      [&](KeyMapJob& job) {
        started = true;
        while (!release) {
          std::this_thread::yield();
        }
        arrived_prepared.push_back(job.described.has_value());
      },
      [&](KeyMapJob& job) {
        job.described = DescribedKeyMap{};
        if (++prepared == 2) {
          release = true;  // the pushing thread prepared both waiting jobs while the queue was full
        }
      },
      2);
  worker.Push(Job(0));
  while (!started) {  // the worker holds job 0
    std::this_thread::yield();
  }
  worker.Push(Job(1));
  worker.Push(Job(2));
  worker.Push(Job(3));  // full: prepares jobs 2 and 1 while it waits for room
  worker.Drain();
  EXPECT_EQ(prepared.load(), 2);
  EXPECT_EQ(arrived_prepared, (std::vector<bool>{false, true, true, false}));
}

TEST(KeyMapWorker, AFailedPreparationIsRethrownByDrain) {
  std::atomic<bool> release{false};
  KeyMapWorker worker(
      [&](KeyMapJob& /*job*/) {
        while (!release) {
          std::this_thread::yield();
        }
      },
      [](KeyMapJob& /*job*/) { throw std::runtime_error("bad key map"); }, 4);
  worker.Push(Job(0));
  worker.Push(Job(1));
  worker.Push(Job(2));
  EXPECT_TRUE(worker.Help(2));
  release = true;
  EXPECT_THROW(worker.Drain(), std::runtime_error);
}

}  // namespace
}  // namespace gridslam::pipeline
