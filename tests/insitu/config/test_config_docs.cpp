// docs/runtime.md lists every config key, and no other, as the schema has it: its "Every key"
// tables are what `voxspan-config --reference` prints (config_reference()).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "insitu/runtime/config_file.h"

namespace voxspan {
namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(ConfigDocs, RuntimeMdListsEveryKeyAsTheSchemaHasIt) {
  const std::string doc = read_file(VOXSPAN_SOURCE_DIR "/docs/runtime.md");
  const std::string begin =
      "<!-- the output of `voxspan-config --reference`, held to it by a test -->\n";
  const std::string end = "<!-- end of the reference -->";
  const std::size_t a = doc.find(begin), b = doc.find(end);
  ASSERT_NE(a, std::string::npos) << "docs/runtime.md has no reference block";
  ASSERT_NE(b, std::string::npos);
  EXPECT_EQ(doc.substr(a + begin.size(), b - a - begin.size()), config_reference())
      << "docs/runtime.md is out of date: paste the output of build/tools/voxspan-config "
         "--reference between its markers";
}

}  // namespace
}  // namespace voxspan
