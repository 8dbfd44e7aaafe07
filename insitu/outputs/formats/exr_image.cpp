#include "insitu/outputs/formats/exr_image.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfVecAttribute.h>
#include <OpenEXR/ImfDeepFrameBuffer.h>
#include <OpenEXR/ImfDeepScanLineOutputFile.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfStdIO.h>

#include <functional>
#include <initializer_list>
#include <utility>
#include <vector>

#include "insitu/outputs/writer/atomic_file.h"
#include "voxspan/error.h"

namespace voxspan {

namespace {

struct Component {
  const char* channel;
  int index;  // 0..3: r, g, b, a
};

// The image's components as FLOAT channels of a ZIP-compressed scanline file, in memory, with
// `annotate` adding to its header.
std::string encode_components(const FloatImage& image, std::initializer_list<Component> components,
                              const char* what,
                              const std::function<void(Imf::Header&)>& annotate = {}) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != 4 * std::size_t(image.width) * std::size_t(image.height))
    throw make_error("EXR image: ", image.width, "x", image.height, " with ", image.rgba.size(),
                     " floats is not an RGBA image");
  try {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    if (annotate) annotate(header);
    Imf::FrameBuffer frame;
    // Rows top first; a component every 4 floats.
    const std::size_t pixel = 4 * sizeof(float);
    char* base = const_cast<char*>(reinterpret_cast<const char*>(image.rgba.data()));
    for (const Component& c : components) {
      header.channels().insert(c.channel, Imf::Channel(Imf::FLOAT));
      frame.insert(c.channel, Imf::Slice(Imf::FLOAT, base + std::size_t(c.index) * sizeof(float),
                                         pixel, pixel * std::size_t(image.width)));
    }
    Imf::StdOSStream stream;
    {
      Imf::OutputFile file(stream, header);
      file.setFrameBuffer(frame);
      file.writePixels(image.height);
    }
    return stream.str();
  } catch (const std::exception& e) {
    throw make_error("OpenEXR could not encode the ", what, " image: ", e.what());
  }
}

}  // namespace

std::string encode_exr_channel(const FloatImage& image, const std::string& channel) {
  return encode_components(image, {{channel.c_str(), 0}}, channel.c_str());
}

std::string encode_exr_rgba(const FloatImage& image) {
  return encode_components(image, {{"R", 0}, {"G", 1}, {"B", 2}, {"A", 3}}, "RGBA");
}

std::string encode_exr_field(const FieldImage& f) {
  return encode_components(f.values, {{"value", 0}, {"weight", 1}}, "slice", [&](Imf::Header& h) {
    const auto v3 = [](glm::dvec3 p) { return Imath::V3d(p.x, p.y, p.z); };
    h.insert("voxspan:quantity", Imf::StringAttribute(f.quantity));
    h.insert("voxspan:origin", Imf::V3dAttribute(v3(f.origin)));
    h.insert("voxspan:u", Imf::V3dAttribute(v3(f.u)));
    h.insert("voxspan:v", Imf::V3dAttribute(v3(f.v)));
    h.insert("voxspan:width", Imf::DoubleAttribute(f.width));
    h.insert("voxspan:height", Imf::DoubleAttribute(f.height));
    h.insert("voxspan:pixel_to_world",
             Imf::StringAttribute("origin + ((i + 0.5) / W - 0.5) * width * u + "
                                  "(0.5 - (j + 0.5) / H) * height * v, row j = 0 at the top"));
  });
}

namespace {

// A deep scanline image of `counts` samples per pixel (row 0 at the top), each of `channels`
// (name, values of every sample in pixel order), ZIPS-compressed.
std::string encode_deep(int width, int height, std::vector<unsigned>& counts,
                        std::vector<std::pair<const char*, std::vector<float>>>& channels) {
  const std::size_t n = counts.size();
  std::vector<std::size_t> first(n + 1, 0);
  for (std::size_t p = 0; p < n; ++p) first[p + 1] = first[p] + counts[p];
  std::vector<std::vector<float*>> at(channels.size(), std::vector<float*>(n));
  for (std::size_t c = 0; c < channels.size(); ++c)
    for (std::size_t p = 0; p < n; ++p) at[c][p] = channels[c].second.data() + first[p];
  try {
    Imf::Header header(width, height);
    header.setType(Imf::DEEPSCANLINE);
    header.compression() = Imf::ZIPS_COMPRESSION;
    for (const auto& [name, values] : channels)
      header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    Imf::DeepFrameBuffer frame;
    frame.insertSampleCountSlice(Imf::Slice(Imf::UINT, reinterpret_cast<char*>(counts.data()),
                                            sizeof(unsigned), sizeof(unsigned) * width));
    for (std::size_t c = 0; c < channels.size(); ++c)
      frame.insert(channels[c].first,
                   Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(at[c].data()), sizeof(float*),
                                  sizeof(float*) * width, sizeof(float)));
    Imf::StdOSStream stream;
    {
      Imf::DeepScanLineOutputFile file(stream, header);
      file.setFrameBuffer(frame);
      file.writePixels(height);
    }
    return stream.str();
  } catch (const std::exception& e) {
    throw make_error("OpenEXR could not encode the deep image: ", e.what());
  }
}

}  // namespace

std::string encode_deep_exr(const SpanImage& spans) {
  const int width = spans.width(), height = spans.height();
  if (width <= 0 || height <= 0 || spans.pixels.size() != std::size_t(width) * height)
    throw make_error("deep EXR image: the span image is ", width, "x", height, " with ",
                     spans.pixels.size(), " pixel records");
  const std::size_t n = spans.pixels.size();
  std::vector<unsigned> counts(n);
  std::vector<std::pair<const char*, std::vector<float>>> channels = {{"Z", {}}, {"ZBack", {}}};
  std::vector<float>& z = channels[0].second;
  std::vector<float>& z_back = channels[1].second;
  z.reserve(spans.spans.size());
  z_back.reserve(spans.spans.size());
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t p = std::size_t(x) + std::size_t(y) * width;
      const double scale = spans.grid.view().ray_scale(x, y);
      counts[p] = spans.pixels[p].count;
      for (const Span& s : spans.spans_at(x, y)) {
        z.push_back(float(double(s.entry) * scale));
        z_back.push_back(float(double(s.exit) * scale));
      }
    }
  return encode_deep(width, height, counts, channels);
}

std::string encode_deep_exr(const DeepImage& deep) {
  const std::size_t n = std::size_t(deep.width) * std::size_t(deep.height);
  if (deep.width <= 0 || deep.height <= 0 || deep.start.size() != n + 1)
    throw make_error("deep EXR image: the deep image is ", deep.width, "x", deep.height, " with ",
                     deep.start.size(), " pixel offsets");
  std::vector<unsigned> counts(n);
  for (std::size_t p = 0; p < n; ++p) counts[p] = deep.start[p + 1] - deep.start[p];
  std::vector<std::pair<const char*, std::vector<float>>> channels = {
      {"Z", {}}, {"ZBack", {}}, {"R", {}}, {"G", {}}, {"B", {}}, {"A", {}}};
  for (const DeepSample& s : deep.samples) {
    const float values[] = {s.z, s.z_back, s.rgba.r, s.rgba.g, s.rgba.b, s.rgba.a};
    for (std::size_t c = 0; c < channels.size(); ++c) channels[c].second.push_back(values[c]);
  }
  return encode_deep(deep.width, deep.height, counts, channels);
}

void write_exr_channel(const std::filesystem::path& path, const FloatImage& image,
                       const std::string& channel, bool sync) {
  write_file_atomically(path, encode_exr_channel(image, channel), sync);
}

}  // namespace voxspan
