// Runs the current test again in a fresh process (fork, then exec of this test binary with a
// filter), after `setup` has run in the forked child: a mount namespace or a resource limit
// made there survives the exec. A process that has made a GL context must not fork and go on
// with GL (Mesa's threads and locks do not survive a fork), so the child starts anew from exec
// and makes its own context (tests only).
//
// The rerun test finds the environment variable VOXSPAN_CHILD_REPORT (a file path) and
// VOXSPAN_CHILD_FOLDER (where to work), does its part and writes its report to the file.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

namespace voxspan::test {

// Inside the rerun: the folder and report path, or nullptr in the ordinary run.
inline const char* child_folder() { return std::getenv("VOXSPAN_CHILD_FOLDER"); }
inline void write_child_report(const std::string& report) {
  std::ofstream(std::getenv("VOXSPAN_CHILD_REPORT")) << report;
}

// `setup` returns "" to go on, or a report (e.g. "skip=why\n") to give back at once. The
// child's wait status goes to `status` when given.
inline std::string run_test_in_fresh_process(const std::filesystem::path& folder,
                                             const std::filesystem::path& report,
                                             const std::function<std::string()>& setup,
                                             int* status = nullptr) {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string filter =
      std::string("--gtest_filter=") + info->test_suite_name() + "." + info->name();
  std::filesystem::remove(report);
  const pid_t pid = ::fork();
  if (pid < 0) return "";
  if (pid == 0) {
    const std::string early = setup();
    if (!early.empty()) {
      std::ofstream(report) << early;
      ::_exit(0);
    }
    ::setenv("VOXSPAN_CHILD_FOLDER", folder.c_str(), 1);
    ::setenv("VOXSPAN_CHILD_REPORT", report.c_str(), 1);
    char self[] = "/proc/self/exe";
    char* argv[] = {self, const_cast<char*>(filter.c_str()), nullptr};
    ::execv(self, argv);
    ::_exit(127);
  }
  int waited = 0;
  ::waitpid(pid, &waited, 0);
  if (status) *status = waited;
  std::ifstream in(report);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace voxspan::test
