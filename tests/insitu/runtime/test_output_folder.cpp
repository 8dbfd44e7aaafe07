// Output folders are checked before step 1: created when missing, refused with a reason.
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <sched.h>
#include <unistd.h>

#include <fstream>

#include "insitu/runtime/config_file.h"
#include "insitu/runtime/output_folder.h"
#include "tests/support/child_process.h"
#include "tests/support/error_message.h"
#include "tests/support/temp_folder.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

std::string error_of(const std::filesystem::path& folder) {
  return test::error_message([&] { prepare_output_folder(folder, "outputs.png folder"); });
}

TEST(OutputFolder, CreatesMissingFoldersAndLeavesNoProbe) {
  test::TempFolder dir;
  std::filesystem::path nested = dir / "a/b/c";
  EXPECT_EQ(error_of(nested), "");
  EXPECT_TRUE(std::filesystem::is_directory(nested));
  EXPECT_TRUE(std::filesystem::is_empty(nested));
  EXPECT_EQ(error_of(nested), "");  // existing is fine too
}

TEST(OutputFolder, RefusesAFileAndAFolderUnderAFile) {
  test::TempFolder dir;
  std::ofstream(dir / "file") << "x";
  std::string e = error_of(dir / "file");
  EXPECT_NE(e.find("cannot use outputs.png folder " + (dir / "file").string()), std::string::npos)
      << e;
  EXPECT_NE(e.find("Not a directory"), std::string::npos) << e;
  e = error_of(dir / "file/sub");
  EXPECT_NE(e.find((dir / "file/sub").string() + ": Not a directory"), std::string::npos) << e;
  EXPECT_NE(error_of("/proc/voxspan-cannot-exist").find("cannot use outputs.png folder /proc/"),
            std::string::npos);
}

// Root writes through permission bits, so the unwritable folder is a read-only mount, made
// in a private mount namespace of a child process (skipped where namespaces are refused).
TEST(OutputFolder, RefusesAReadOnlyFolder) {
  test::TempFolder dir;
  std::filesystem::path ro = dir / "ro";
  std::filesystem::create_directories(ro);
  if (::geteuid() != 0) {
    std::filesystem::permissions(
        ro, std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
    std::string e = error_of(ro);
    EXPECT_NE(e.find("cannot create a file in it (Permission denied)"), std::string::npos) << e;
    return;
  }
  std::string message = test::run_in_child([&]() -> std::string {
    if (::unshare(CLONE_NEWNS) != 0 ||
        ::mount(nullptr, "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0 ||
        ::mount("tmpfs", ro.c_str(), "tmpfs", MS_RDONLY, "size=64k") != 0)
      return "SKIP";
    return error_of(ro);
  });
  if (message == "SKIP") GTEST_SKIP() << "no mount namespace here";
  EXPECT_NE(message.find("cannot use outputs.png folder " + ro.string() +
                         ": cannot create a file in it (Read-only file system)"),
            std::string::npos)
      << message;
}

TEST(OutputFolder, ChecksTheFolderOfEveryEnabledOutput) {
  test::TempFolder dir;
  std::ofstream(dir / "blocker") << "x";
  Config c = load_config_string(
      "output_folder: " + dir.path().string() +
      "\noutputs:\n  png: {folder: frames}\n  vdb: {enabled: true, folder: blocker/snap}\n");
  try {
    prepare_output_folders(c);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot use outputs.vdb folder " +
                                         (dir / "blocker/snap").string()),
              std::string::npos)
        << e.what();
  }
  c.output("vdb").folder = "snap";
  std::vector<std::filesystem::path> made = prepare_output_folders(c);
  EXPECT_EQ(made, std::vector<std::filesystem::path>{dir / "snap"});  // the others existed
  EXPECT_TRUE(std::filesystem::is_directory(dir / "frames"));
  EXPECT_TRUE(std::filesystem::is_directory(dir / "snap"));
  EXPECT_FALSE(std::filesystem::exists(dir / "vtk"));  // vtk is off
}

}  // namespace
}  // namespace voxspan
