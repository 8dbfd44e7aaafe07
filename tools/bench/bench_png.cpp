// bench_png: the PNG frames' encoding (insitu/outputs/formats/png_image.h) on rendered pictures,
// per candidate: the time one writer thread takes to encode a frame and the file's bytes. The
// pictures are bench_renderers' dam break shaded by the CPU renderer (render/cpu/cpu_renderer.h)
// at each --sizes size, in --mode (the runtime's default, translucent), converted to 8-bit sRGB
// as the PNG output does. The candidates:
//   libpng fast      libpng's simplified writer with PNG_IMAGE_FLAG_FAST (zlib level 3, no
//                    filter): the encoder before libdeflate
//   libpng default   libpng's own defaults (zlib level 6, adaptive filters)
//   libpng L F       libpng at zlib level L (--libpng-levels), filter F (--filters)
//   deflate L F      the PNG output's encoder (libdeflate) at level L (--levels), filter F
//   outputs.png default  the output's encoder at its default (PngEncoding{})
// Each picture is encoded --runs times after one warm-up (median ms, one thread: the writer's),
// and every candidate's file is decoded by libpng and compared with the picture: a mismatch
// stops the tool (exit 1). Also timed: the sRGB conversion before the encoding.
//
//   bench_png [--particles N] [--time T] [--state FILE] [--ritter] [--sizes WxH,...]
//             [--mode opaque|translucent|refractive] [--runs R] [--levels 1,4,6]
//             [--libpng-levels 1,2,3] [--filters none,sub,up,paeth,adaptive] [--csv FILE]
#include <png.h>

#include <cstdio>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "insitu/outputs/formats/png_image.h"
#include "render/cpu/cpu_renderer.h"
#include "tools/common/dambreak_state.h"
#include "tools/common/tool_args.h"
#include "voxspan/error.h"
#include "voxspan/stopwatch.h"

namespace {

using namespace voxspan;

constexpr EnumName<PngFilter> kFilterNames[] = {
    {"none", PngFilter::none},   {"sub", PngFilter::sub},
    {"up", PngFilter::up},       {"average", PngFilter::average},
    {"paeth", PngFilter::paeth}, {"adaptive", PngFilter::adaptive}};

struct Args : tools::SceneArgs, tools::StateFlags {
  std::vector<std::pair<int, int>> sizes = {{640, 360}, {1920, 1080}};
  ShadeMode mode = ShadeMode::translucent;
  int runs = 5;
  std::vector<int> levels = {1, 4, 6};
  std::vector<int> libpng_levels = {1, 2, 3};
  std::vector<PngFilter> filters = {PngFilter::none, PngFilter::sub, PngFilter::up,
                                    PngFilter::paeth, PngFilter::adaptive};
  std::string csv;
};

constexpr char kUsage[] =
    "usage: bench_png [--particles N] [--time T] [--state FILE] [--ritter] [--sizes WxH,...]\n"
    "         [--mode opaque|translucent|refractive] [--runs R] [--levels 1,4,6]\n"
    "         [--libpng-levels 1,2,3] [--filters none,sub,up,paeth,adaptive] [--csv FILE]\n";

bool read_ints(const char* list, int lo, int hi, std::vector<int>& out) {
  out.clear();
  for (const std::string& item : tools::comma_list(list)) {
    char* end = nullptr;
    const long v = std::strtol(item.c_str(), &end, 10);
    if (end == item.c_str() || *end != '\0' || v < lo || v > hi) return false;
    out.push_back(int(v));
  }
  return !out.empty();
}

bool read_flag(tools::Arg& arg, Args& a) {
  if (const char* v = arg.value("--sizes")) {
    a.sizes.clear();
    for (const std::string& s : tools::comma_list(v)) {
      int w = 0, h = 0;
      if (!tools::parse_size(s.c_str(), w, h)) return false;
      a.sizes.push_back({w, h});
    }
    return !a.sizes.empty();
  }
  if (const char* v = arg.value("--mode")) {
    std::vector<ShadeMode> modes;
    if (!tools::read_names(v, kShadeModeNames, modes) || modes.size() != 1) return false;
    a.mode = modes[0];
    return true;
  }
  if (const char* v = arg.value("--levels")) return read_ints(v, 0, 12, a.levels);
  if (const char* v = arg.value("--libpng-levels")) return read_ints(v, 0, 9, a.libpng_levels);
  if (const char* v = arg.value("--filters")) return tools::read_names(v, kFilterNames, a.filters);
  if (arg.value("--runs", a.runs)) return a.runs >= 1;
  return arg.value("--csv", a.csv) || tools::read_state_flag(arg, a);
}

bool parse(int argc, char** argv, Args& a) { return tools::read_args(argc, argv, a, read_flag); }

// ---- libpng's encoders

// libpng's simplified writer with PNG_IMAGE_FLAG_FAST: the PNG output's encoder before
// libdeflate, as it was.
std::string libpng_simplified(const ImageRGBA8& p) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = png_uint_32(p.width);
  image.height = png_uint_32(p.height);
  image.format = PNG_FORMAT_RGBA;
  image.flags = PNG_IMAGE_FLAG_FAST;
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&image, nullptr, &size, 0, p.pixels.data(), 0, nullptr))
    throw make_error("libpng: ", image.message);
  std::string bytes(size, '\0');
  if (!png_image_write_to_memory(&image, bytes.data(), &size, 0, p.pixels.data(), 0, nullptr))
    throw make_error("libpng: ", image.message);
  bytes.resize(size);
  return bytes;
}

int libpng_filter(PngFilter f) {
  switch (f) {
    case PngFilter::none: return PNG_FILTER_NONE;
    case PngFilter::sub: return PNG_FILTER_SUB;
    case PngFilter::up: return PNG_FILTER_UP;
    case PngFilter::average: return PNG_FILTER_AVG;
    case PngFilter::paeth: return PNG_FILTER_PAETH;
    case PngFilter::adaptive: return PNG_ALL_FILTERS;
  }
  return PNG_ALL_FILTERS;
}

// libpng's full writer at zlib level `level` (< 0: libpng's default) and `filter` (adaptive:
// libpng's own heuristic over all five), with the sRGB chunk.
std::string libpng_at(const ImageRGBA8& p, int level, PngFilter filter, bool defaults = false) {
  std::string out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png != nullptr ? png_create_info_struct(png) : nullptr;
  if (info == nullptr) throw make_error("libpng: out of memory");
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw make_error("libpng failed");
  }
  png_set_write_fn(
      png, &out,
      [](png_structp s, png_bytep data, png_size_t n) {
        static_cast<std::string*>(png_get_io_ptr(s))->append(reinterpret_cast<char*>(data), n);
      },
      nullptr);
  png_set_IHDR(png, info, png_uint_32(p.width), png_uint_32(p.height), 8, PNG_COLOR_TYPE_RGBA,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  if (!defaults) {
    png_set_compression_level(png, level);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, libpng_filter(filter));
  }
  png_write_info(png, info);
  for (int y = 0; y < p.height; ++y)
    png_write_row(png, p.pixels.data() + std::size_t(y) * std::size_t(p.width) * 4);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return out;
}

// ---- the table

struct Candidate {
  std::string name;
  std::function<std::string(const ImageRGBA8&)> encode;
};

std::vector<Candidate> candidates(const Args& a) {
  std::vector<Candidate> c;
  c.push_back({"libpng fast (before)", libpng_simplified});
  c.push_back({"libpng default (6, adaptive)",
               [](const ImageRGBA8& p) { return libpng_at(p, -1, PngFilter::adaptive, true); }});
  for (int level : a.libpng_levels)
    for (PngFilter f : a.filters)
      c.push_back({"libpng " + std::to_string(level) + " " + std::string(name_of(kFilterNames, f)),
                   [level, f](const ImageRGBA8& p) { return libpng_at(p, level, f); }});
  for (int level : a.levels)
    for (PngFilter f : a.filters)
      c.push_back({"deflate " + std::to_string(level) + " " + std::string(name_of(kFilterNames, f)),
                   [e = PngEncoding{level, f}](const ImageRGBA8& p) { return encode_png(p, e); }});
  c.push_back({"outputs.png default (4 sub)", [](const ImageRGBA8& p) { return encode_png(p); }});
  return c;
}

int run(const Args& a) {
  tools::DamBreakState s = tools::dam_break_state(a, a);
  ShadeOptions shade = tools::bench_shading(s);
  shade.mode = a.mode;
  SpanOptions spans;
  spans.gap_bridging = s.spacing;
  spans.grid.alpha_degrees = a.alpha;
  SurfaceOptions surfaces;
  surfaces.filter_radius = s.spacing;

  std::vector<ImageRGBA8> pictures;
  std::printf("scene: %s, %s\n", s.description.c_str(), shade_mode_name(a.mode));
  for (auto [w, h] : a.sizes) {
    s.camera.width = w;
    s.camera.height = h;
    CpuRenderer renderer;
    FrameStats stats;
    Recorder recorder(stats);
    const SpanImage& cast = renderer.cast(s.camera, s.classification.boundary,
                                          s.classification.cell_states(), spans, recorder);
    const FloatImage& picture = renderer.shade(cast, surfaces, shade, recorder);
    std::vector<double> ms;
    for (int r = -1; r < a.runs; ++r) {
      const Stopwatch watch;
      pictures.push_back(linear_to_srgb8(picture.rgba, picture.width, picture.height));
      if (r >= 0) ms.push_back(watch.ms());
      if (r < a.runs - 1) pictures.pop_back();
    }
    std::printf("%dx%d: sRGB conversion (before any encoder) %.1f ms, raw RGBA %zu bytes\n", w, h,
                tools::median(ms), pictures.back().pixels.size());
  }
  std::printf(
      "median ms of %d encodings after a warm-up, one thread; bytes; every file decoded "
      "by libpng to the same pixels\n\n",
      a.runs);

  std::ofstream csv;
  if (!a.csv.empty()) {
    csv.open(a.csv);
    if (!csv) throw make_error("cannot write ", a.csv);
    csv << "candidate,width,height,median_ms,bytes\n";
  }
  std::printf("%-30s", "candidate");
  for (const ImageRGBA8& p : pictures) {
    const std::string size = std::to_string(p.width) + "x" + std::to_string(p.height);
    std::printf(" %9s %11s", (size + " ms").c_str(), "bytes");
  }
  std::printf("\n");
  for (const Candidate& c : candidates(a)) {
    std::printf("%-30s", c.name.c_str());
    for (const ImageRGBA8& p : pictures) {
      std::vector<double> ms;
      std::string bytes;
      for (int r = -1; r < a.runs; ++r) {
        const Stopwatch watch;
        bytes = c.encode(p);
        if (r >= 0) ms.push_back(watch.ms());
      }
      const ImageRGBA8 back = decode_png(bytes);
      if (back.width != p.width || back.height != p.height || back.pixels != p.pixels)
        throw make_error(c.name, " at ", p.width, "x", p.height,
                         ": libpng decodes other pixels than were encoded");
      std::printf(" %9.1f %11zu", tools::median(ms), bytes.size());
      std::fflush(stdout);
      if (csv)
        csv << '"' << c.name << "\"," << p.width << ',' << p.height << ',' << tools::median(ms)
            << ',' << bytes.size() << '\n';
    }
    std::printf("\n");
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return voxspan::tools::tool_main<Args>("bench_png", argc, argv, kUsage, parse, run);
}
