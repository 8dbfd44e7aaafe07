#include "render/gl/shader_library.h"

#include <algorithm>

#include "voxspan/error.h"

namespace voxspan::gl {

std::string defines(std::initializer_list<Define> list) {
  std::string out;
  for (const Define& d : list) {
    out += "#define ";
    out += d.name;
    out += ' ' + std::to_string(d.value) + '\n';
  }
  return out;
}

ShaderLibrary::ShaderLibrary(std::initializer_list<std::span<const EmbeddedFile>> extra) {
  auto add = [this](std::span<const EmbeddedFile> set) {
    files_.insert(files_.end(), set.begin(), set.end());
  };
  add(embedded::render_shaders());
  for (auto set : extra) add(set);
}

std::string_view ShaderLibrary::source(std::string_view path) const {
  auto it = std::find_if(files_.begin(), files_.end(),
                         [&](const EmbeddedFile& f) { return f.path == path; });
  if (it == files_.end()) throw make_error("no embedded shader named ", path);
  return it->text;
}

void ShaderLibrary::expand(std::string_view path, std::string& out,
                           std::vector<std::string>& files) const {
  if (std::find(files.begin(), files.end(), path) != files.end()) return;  // once per program
  std::string_view text = source(path);
  files.emplace_back(path);
  const std::size_t index = files.size() - 1;
  out += "#line 1 " + std::to_string(index) + "\n";
  int line = 0;
  while (!text.empty()) {
    std::size_t end = text.find('\n');
    std::string_view l = text.substr(0, end);
    text.remove_prefix(end == std::string_view::npos ? text.size() : end + 1);
    ++line;
    constexpr std::string_view kInclude = "#include \"";
    if (l.starts_with(kInclude) && l.ends_with('"')) {
      expand(l.substr(kInclude.size(), l.size() - kInclude.size() - 1), out, files);
      out += "#line " + std::to_string(line + 1) + " " + std::to_string(index) + "\n";
      continue;
    }
    out.append(l);
    out += '\n';
  }
}

std::string ShaderLibrary::compose(std::string_view path, std::string_view defines,
                                   std::vector<std::string>& files) const {
  std::string out = "#version 450 core\n";
  out.append(defines);
  if (!defines.empty() && defines.back() != '\n') out += '\n';
  files.clear();
  expand(path, out, files);
  return out;
}

Program ShaderLibrary::compute(std::string_view path, std::string_view defines) const {
  std::vector<std::string> files;
  std::string source = compose(path, defines, files);
  try {
    return Program::compute(path, source);
  } catch (const Error& e) {
    std::string names;
    for (std::size_t i = 0; i < files.size(); ++i)
      names += "\n  file " + std::to_string(i) + ": " + files[i];
    throw Error(e.what() + names);
  }
}

}  // namespace voxspan::gl
