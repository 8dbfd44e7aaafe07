// render/gl/shader_library.h - builds compute programs from embedded GLSL files.
//
// GLSL files carry no #version line; compose() prepends "#version 450 core", the caller's
// #defines, and expands `#include "path"` lines (paths relative to the repository root, each
// file included once), so passes share helpers instead of copying them. Each expanded file
// starts with `#line 1 <n>`: a compiler message "n:line" names file n of the list the error
// message prints. Numbers a pass hands its shader (binding points, sizes) go in as #defines built
// by defines(), so the shader never writes them itself.
#pragma once

#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "render/gl/embedded.h"
#include "render/gl/objects.h"

namespace voxspan::gl {

// One constant for a shader: `#define name value`.
struct Define {
  std::string_view name;
  unsigned value;
};

// "#define name value\n" per entry, for ShaderLibrary::compute().
std::string defines(std::initializer_list<Define> list);

class ShaderLibrary {
 public:
  // The render shaders, plus any extra sets (tests add their own).
  explicit ShaderLibrary(std::initializer_list<std::span<const EmbeddedFile>> extra = {});

  std::string_view source(std::string_view path) const;  // throws if unknown
  // Full source and the list of file names in #line order.
  std::string compose(std::string_view path, std::string_view defines,
                      std::vector<std::string>& files) const;
  // compose() + Program::compute(); compile errors name the files.
  Program compute(std::string_view path, std::string_view defines = {}) const;

 private:
  void expand(std::string_view path, std::string& out, std::vector<std::string>& files) const;
  std::vector<EmbeddedFile> files_;
};

}  // namespace voxspan::gl
