// voxspan-config: checks an in-situ config file and prints it as the runtime reads it, every
// key with its value (defaults included), or prints the reference of every key.
//
//   voxspan-config FILE          errors (file:line:col: key path: ...) and exit 1, or the
//                                effective config as YAML and exit 0
//   voxspan-config               the defaults, as YAML
//   voxspan-config --reference   the tables of every key, type, default and meaning (markdown:
//                                docs/runtime.md holds them as this prints them)
#include <cstdio>
#include <string>

#include "insitu/runtime/config_file.h"
#include "tools/common/usage.h"
#include "voxspan/error.h"

namespace {

constexpr const char* kUsage =
    "usage: voxspan-config [FILE | --reference]\n"
    "  FILE         check an in-situ config file; print it as the runtime reads it (YAML)\n"
    "  (none)       print the defaults (YAML)\n"
    "  --reference  print the reference of every key (markdown tables)\n";

}  // namespace

int main(int argc, char** argv) {
  using voxspan::tools::print_usage;
  const std::string arg = argc == 2 ? argv[1] : "";
  if (argc > 2 || (arg.starts_with("-") && arg != "--reference" && arg != "-h" && arg != "--help"))
    return print_usage(stderr, kUsage);
  if (arg == "-h" || arg == "--help") return print_usage(stdout, kUsage);
  try {
    if (arg == "--reference") std::fputs(voxspan::config_reference().c_str(), stdout);
    else if (arg.empty()) std::fputs(voxspan::to_yaml(voxspan::default_config()).c_str(), stdout);
    else std::fputs(voxspan::to_yaml(voxspan::load_config_file(arg)).c_str(), stdout);
  } catch (const voxspan::Error& e) {
    std::fprintf(stderr, "voxspan-config: %s\n", e.what());
    return 1;
  }
  return 0;
}
