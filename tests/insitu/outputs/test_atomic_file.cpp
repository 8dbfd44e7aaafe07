// Files appear under their final name only when complete.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "insitu/outputs/writer/atomic_file.h"
#include "tests/support/temp_folder.h"

namespace voxspan {
namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(AtomicFile, CommitRenamesAndLeavesNoTemporary) {
  test::TempFolder dir;
  {
    AtomicFile f(dir / "a.txt");
    EXPECT_EQ(f.temp_path().parent_path(), dir.path());
    f.write("hello ");
    f.stream() << "world";
    EXPECT_FALSE(std::filesystem::exists(dir / "a.txt"));
    EXPECT_TRUE(std::filesystem::exists(f.temp_path()));
    f.commit();
    EXPECT_EQ(f.bytes_written(), 11u);
  }
  EXPECT_EQ(slurp(dir / "a.txt"), "hello world");
  EXPECT_EQ(test::count_temp_files(dir.path()), 0u);
}

TEST(AtomicFile, AbandonedFilesLeaveNothing) {
  test::TempFolder dir;
  try {
    AtomicFile f(dir / "b.bin");
    f.write(std::string(200000, 'x'));
    throw std::runtime_error("the job failed half-way");
  } catch (const std::runtime_error&) {}
  EXPECT_FALSE(std::filesystem::exists(dir / "b.bin"));
  EXPECT_EQ(test::count_temp_files(dir.path()), 0u);
}

TEST(AtomicFile, ReplacesAnOldFileOnlyAtCommit) {
  test::TempFolder dir;
  write_file_atomically(dir / "c.txt", "old");
  AtomicFile f(dir / "c.txt");
  f.write("new content");
  EXPECT_EQ(slurp(dir / "c.txt"), "old");
  f.commit(false);
  EXPECT_EQ(slurp(dir / "c.txt"), "new content");
}

TEST(AtomicFile, StreamIsSeekable) {
  test::TempFolder dir;
  AtomicFile f(dir / "d.bin");
  std::ostream& s = f.stream();
  s << "0123456789";
  std::streampos at = s.tellp();
  EXPECT_EQ(at, std::streampos(10));
  s.seekp(2);
  s << "ab";
  s.seekp(0, std::ios::end);
  s << "!";
  f.commit();
  EXPECT_EQ(slurp(dir / "d.bin"), "01ab456789!");
}

TEST(AtomicFile, MissingFolderIsAWriteErrorNamingTheFile) {
  test::TempFolder dir;
  try {
    AtomicFile f(dir / "no/such/e.txt");
    FAIL() << "no error";
  } catch (const WriteError& e) {
    EXPECT_EQ(e.error_number(), ENOENT);
    EXPECT_NE(std::string(e.what()).find("cannot create " + (dir / "no/such/").string()),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace voxspan
