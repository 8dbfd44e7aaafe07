// The background writer: order, bounded queue with wait/drop, failures reported once.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "insitu/outputs/writer/atomic_file.h"
#include "insitu/outputs/writer/background_writer.h"
#include "tests/support/log_capture.h"

namespace voxspan {
namespace {

// Holds the writer thread inside a job until released.
class Gate {
 public:
  void wait() {
    std::unique_lock lock(m_);
    entered_ = true;
    cv_.notify_all();
    cv_.wait(lock, [&] { return open_; });
  }
  void wait_entered() {
    std::unique_lock lock(m_);
    cv_.wait(lock, [&] { return entered_; });
  }
  void open() {
    std::lock_guard lock(m_);
    open_ = true;
    cv_.notify_all();
  }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  bool open_ = false, entered_ = false;
};

TEST(BackgroundWriter, RunsJobsInOrderAndDrainWaitsForThem) {
  std::vector<int> done;
  BackgroundWriter w(4, QueuePolicy::wait);
  for (int i = 0; i < 50; ++i)
    EXPECT_TRUE(w.submit("job", [&done, i] {
      std::this_thread::sleep_for(std::chrono::microseconds(50));
      done.push_back(i);
    }));
  w.drain();
  ASSERT_EQ(done.size(), 50u);
  for (int i = 0; i < 50; ++i) EXPECT_EQ(done[std::size_t(i)], i);
  WriterStats s = w.stats();
  EXPECT_EQ(s.submitted, 50u);
  EXPECT_EQ(s.completed, 50u);
  EXPECT_LE(s.max_queued, 4u);
}

TEST(BackgroundWriter, WaitPolicyBlocksTheCallerUntilThereIsRoom) {
  Gate gate;
  BackgroundWriter w(2, QueuePolicy::wait);
  w.submit("blocker", [&] { gate.wait(); });
  gate.wait_entered();
  w.submit("a", [] {});
  w.submit("b", [] {});
  std::atomic<bool> third_accepted{false};
  std::thread producer([&] {
    w.submit("c", [] {});
    third_accepted = true;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_FALSE(third_accepted.load());  // the queue is full and the policy is wait
  gate.open();
  producer.join();
  w.drain();
  EXPECT_TRUE(third_accepted.load());
  EXPECT_EQ(w.stats().completed, 4u);
  EXPECT_EQ(w.stats().waits, 1u);
  EXPECT_EQ(w.stats().dropped, 0u);
}

TEST(BackgroundWriter, DropPolicyNeverBlocksAndCountsWithAWarning) {
  test::LogCapture log;
  Gate gate;
  std::atomic<int> ran{0};
  {
    BackgroundWriter w(3, QueuePolicy::drop);
    w.submit("blocker", [&] { gate.wait(); });
    gate.wait_entered();
    int accepted = 0;
    for (int i = 0; i < 25; ++i) accepted += w.submit("frame " + std::to_string(i), [&] { ++ran; });
    EXPECT_EQ(accepted, 3);
    EXPECT_EQ(w.stats().dropped, 22u);
    gate.open();
    w.drain();
    EXPECT_EQ(ran.load(), 3);
  }
  std::vector<std::string> warnings = log.at(LogLevel::warning);
  // At the 1st and 10th drop, then the summary when the writer closes.
  ASSERT_EQ(warnings.size(), 3u) << log.all();
  EXPECT_NE(warnings[0].find("writer queue full (3 jobs): dropped frame 3; 1 file dropped so far"),
            std::string::npos)
      << warnings[0];
  EXPECT_NE(warnings[1].find("10 files dropped so far"), std::string::npos) << warnings[1];
  EXPECT_NE(warnings[2].find("22 files were dropped"), std::string::npos) << warnings[2];
}

// The solver's last step: its files are kept even under `drop` (finish() waits for them).
TEST(BackgroundWriter, AfterKeepEveryFileAFullQueueWaitsUnderDrop) {
  Gate gate;
  std::atomic<int> ran{0};
  BackgroundWriter w(2, QueuePolicy::drop);
  w.submit("blocker", [&] { gate.wait(); });
  gate.wait_entered();
  w.keep_every_file();
  std::thread opener([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    gate.open();
  });
  for (int i = 0; i < 6; ++i) EXPECT_TRUE(w.submit("last " + std::to_string(i), [&] { ++ran; }));
  opener.join();
  w.drain();
  EXPECT_EQ(ran.load(), 6);
  EXPECT_EQ(w.stats().dropped, 0u);
  EXPECT_GT(w.stats().waits, 0u);
}

TEST(BackgroundWriter, EachKindOfFailureIsReportedOnceThenCounted) {
  test::LogCapture log;
  BackgroundWriter w(8, QueuePolicy::wait);
  auto full = [] { throw WriteError("cannot write /out/f.png: No space left on device", ENOSPC); };
  for (int i = 0; i < 5; ++i) {
    w.submit("frame " + std::to_string(i), full);
    w.submit("stats line", [] {});  // small writes that still fit do not re-arm the message
  }
  w.drain();
  EXPECT_EQ(w.stats().failed, 5u);
  EXPECT_EQ(w.stats().completed, 5u);
  EXPECT_EQ(w.stats().first_error, "cannot write /out/f.png: No space left on device");
  std::vector<std::string> errors = log.at(LogLevel::error);
  ASSERT_EQ(errors.size(), 1u) << log.all();
  EXPECT_NE(errors[0].find("writer: frame 0 not written: cannot write /out/f.png: No space left"),
            std::string::npos)
      << errors[0];
  w.submit("frame 9", [] { throw std::runtime_error("VTK could not encode"); });
  w.submit("frame 10", [] { throw WriteError("cannot write: File too large", EFBIG); });
  w.submit("frame 11", [] { throw WriteError("cannot write: File too large", EFBIG); });
  w.drain();
  errors = log.at(LogLevel::error);
  ASSERT_EQ(errors.size(), 3u) << log.all();  // one per new kind
  EXPECT_NE(errors[1].find("frame 9"), std::string::npos);
  EXPECT_NE(errors[2].find("frame 10"), std::string::npos);
  EXPECT_EQ(w.stats().failed, 8u);
}

TEST(BackgroundWriter, DestructorDrainsPendingJobs) {
  std::atomic<int> ran{0};
  {
    BackgroundWriter w(64, QueuePolicy::wait);
    for (int i = 0; i < 40; ++i)
      w.submit("x", [&] {
        std::this_thread::sleep_for(std::chrono::microseconds(100));
        ++ran;
      });
  }
  EXPECT_EQ(ran.load(), 40);
}

}  // namespace
}  // namespace voxspan
