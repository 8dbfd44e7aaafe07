// A disk that fills mid-run, for real: the writer runs in a child process whose output folder
// is a 200 KiB tmpfs (a private mount namespace), or whose file size is capped with
// RLIMIT_FSIZE. The solver side goes on, the error is logged once, and no partial file keeps
// a final name; the stats file holds only complete lines.
#include <gtest/gtest.h>
#include <sched.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/resource.h>
#include <unistd.h>

#include <fstream>
#include <functional>
#include <map>
#include <sstream>

#include "insitu/outputs/formats/stats_log.h"
#include "insitu/outputs/formats/stats_record.h"
#include "insitu/outputs/writer/atomic_file.h"
#include "insitu/outputs/writer/background_writer.h"
#include "tests/support/child_process.h"
#include "tests/support/log_capture.h"
#include "tests/support/temp_folder.h"

namespace voxspan {
namespace {

std::map<std::string, std::string> parse_report(const std::string& text) {
  std::map<std::string, std::string> m;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    auto eq = line.find('=');
    if (eq != std::string::npos) m[line.substr(0, eq)] += line.substr(eq + 1);
  }
  return m;
}

char pattern(std::size_t file, std::size_t i) { return char('a' + (file * 7 + i) % 26); }

// The "solver": 12 steps, each submitting one file of `size(step)` bytes and one stats line.
// Afterwards it reports what the folder holds and whether each final file is complete.
std::string simulate_run(const std::filesystem::path& folder,
                         std::function<std::size_t(int)> size) {
  test::LogCapture log;
  int steps_done = 0;
  {
    BackgroundWriter writer(4, QueuePolicy::wait);
    auto stats_log = std::make_shared<StatsLog>(folder / "stats.jsonl");
    for (int step = 0; step < 12; ++step) {
      std::size_t bytes = size(step);
      writer.submit("frame " + std::to_string(step), [folder, step, bytes] {
        AtomicFile f(folder / ("frame_" + std::to_string(step) + ".bin"));
        std::string data(bytes, '\0');
        for (std::size_t i = 0; i < bytes; ++i) data[i] = pattern(std::size_t(step), i);
        f.write(data);
        f.commit(true);
      });
      StatsRecord record;
      record.step = step;
      record.totals.add_count("particles", 100000 + step);
      record.totals.add_time("splat", 12.5);
      writer.submit("stats", [stats_log, line = to_json_line(record)] { stats_log->append(line); });
      ++steps_done;  // the solver goes on whatever the disk does
    }
    writer.drain();
    WriterStats s = writer.stats();
    std::ostringstream r;
    r << "failed=" << s.failed << "\ncompleted=" << s.completed << "\n";
    r << "first_error=" << s.first_error << "\n";
    r << "errors=" << log.at(LogLevel::error).size() << "\n";
    r << "steps=" << steps_done << "\n";
    std::size_t finals = 0, complete = 0, temps = 0;
    for (const auto& e : std::filesystem::directory_iterator(folder)) {
      std::string name = e.path().filename().string();
      if (name.find(".tmp.") != std::string::npos) {
        ++temps;
        continue;
      }
      if (name.rfind("frame_", 0) != 0) continue;
      ++finals;
      std::size_t index = std::stoul(name.substr(6));
      std::ifstream in(e.path(), std::ios::binary);
      std::string data((std::istreambuf_iterator<char>(in)), {});
      bool ok = data.size() == size(int(index));
      for (std::size_t i = 0; ok && i < data.size(); ++i) ok = data[i] == pattern(index, i);
      complete += ok;
    }
    r << "finals=" << finals << "\ncomplete=" << complete << "\ntemps=" << temps << "\n";
    std::ifstream stats_in(folder / "stats.jsonl", std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(stats_in)), {});
    std::size_t lines = 0, good_lines = 0;
    std::istringstream ls(text);
    for (std::string line; std::getline(ls, line);) {
      ++lines;
      good_lines += line.rfind("{\"step\":", 0) == 0 && line.back() == '}';
    }
    r << "stats_complete=" << (text.empty() || text.back() == '\n') << "\n";
    r << "stats_lines=" << lines << "\nstats_good=" << good_lines << "\n";
    return r.str();
  }
}

void expect_run_survived(const std::map<std::string, std::string>& r, const char* errno_text) {
  EXPECT_EQ(r.at("steps"), "12");
  EXPECT_GE(std::stoul(r.at("failed")), 1u);
  EXPECT_GE(std::stoul(r.at("completed")), 1u);
  EXPECT_NE(r.at("first_error").find(errno_text), std::string::npos) << r.at("first_error");
  EXPECT_EQ(r.at("errors"), "1");               // reported once
  EXPECT_EQ(r.at("temps"), "0");                // temporaries removed
  EXPECT_EQ(r.at("finals"), r.at("complete"));  // no partial file under a final name
  EXPECT_EQ(r.at("stats_complete"), "1");       // the stats file ends with a whole line
  EXPECT_EQ(r.at("stats_lines"), r.at("stats_good"));
}

TEST(DiskFull, SmallTmpfsFillsMidRun) {
  test::TempFolder dir;
  std::filesystem::path mount_point = dir / "small";
  std::filesystem::create_directories(mount_point);
  std::string report = test::run_in_child([&]() -> std::string {
    bool root = ::geteuid() == 0;
    uid_t uid = ::geteuid();
    gid_t gid = ::getegid();
    if (::unshare(root ? CLONE_NEWNS : (CLONE_NEWUSER | CLONE_NEWNS)) != 0) return "skip=unshare\n";
    if (!root) {  // map ourselves to root of the new user namespace
      std::ofstream("/proc/self/setgroups") << "deny";
      std::ofstream("/proc/self/uid_map") << "0 " << uid << " 1";
      std::ofstream("/proc/self/gid_map") << "0 " << gid << " 1";
    }
    if (::mount(nullptr, "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0) return "skip=private\n";
    if (::mount("tmpfs", mount_point.c_str(), "tmpfs", 0, "size=200k") != 0) return "skip=mount\n";
    return simulate_run(mount_point, [](int) { return std::size_t(64) << 10; });
  });
  auto r = parse_report(report);
  if (r.count("skip"))
    GTEST_SKIP() << "this machine allows no tmpfs mount in a namespace (" << r["skip"] << ")";
  ASSERT_TRUE(r.count("failed")) << report;
  expect_run_survived(r, "No space left on device");
  EXPECT_GE(std::stoul(r.at("finals")), 2u);  // 200 KiB holds a few 64 KiB frames
  EXPECT_LE(std::stoul(r.at("finals")), 3u);
}

TEST(DiskFull, FileSizeLimitFailsLargeFilesOnly) {
  test::TempFolder dir;
  std::string report = test::run_in_child([&]() -> std::string {
    ::signal(SIGXFSZ, SIG_IGN);  // so write(2) returns EFBIG instead of killing the process
    struct rlimit limit {
      100 << 10, 100 << 10
    };
    if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) return "skip=setrlimit\n";
    // Odd steps write 256 KiB (over the limit), even steps 16 KiB.
    return simulate_run(dir.path(),
                        [](int step) { return std::size_t(step % 2 ? 256 : 16) << 10; });
  });
  auto r = parse_report(report);
  ASSERT_FALSE(r.count("skip")) << report;
  ASSERT_TRUE(r.count("failed")) << report;
  expect_run_survived(r, "File too large");
  EXPECT_EQ(r.at("failed"), "6");
  EXPECT_EQ(r.at("finals"), "6");
  EXPECT_EQ(r.at("stats_lines"), "12");
}

}  // namespace
}  // namespace voxspan
