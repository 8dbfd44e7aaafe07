// tests/support/deep_exr_reader.h - a deep scanline OpenEXR file read with OpenEXR's own reader
// (tests only): per pixel, row 0 at the top, the samples of channels Z and ZBack, and R, G, B,
// A where the file has them.
#pragma once

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDeepFrameBuffer.h>
#include <OpenEXR/ImfDeepScanLineInputFile.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfPartType.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace voxspan::test {

struct DeepExr {
  std::string type;  // the header's part type: "deepscanline"
  int width = 0, height = 0;
  bool has_z = false, has_z_back = false, has_rgba = false;
  // per pixel, its samples of each channel (empty where the file has none)
  std::vector<std::vector<float>> z, z_back, r, g, b, a;
};

inline DeepExr read_deep_exr(const std::filesystem::path& path) {
  Imf::DeepScanLineInputFile file(path.c_str());
  DeepExr d;
  d.type = file.header().type();
  const Imath::Box2i window = file.header().dataWindow();
  d.width = window.max.x - window.min.x + 1;
  d.height = window.max.y - window.min.y + 1;
  const auto has = [&](const char* name) {
    return file.header().channels().findChannel(name) != nullptr;
  };
  d.has_z = has("Z");
  d.has_z_back = has("ZBack");
  d.has_rgba = has("R") && has("G") && has("B") && has("A");
  const std::size_t n = std::size_t(d.width) * std::size_t(d.height);
  const std::size_t row = std::size_t(d.width);
  std::vector<std::pair<const char*, std::vector<std::vector<float>>*>> channels = {
      {"Z", &d.z}, {"ZBack", &d.z_back}};
  if (d.has_rgba)
    for (const auto& c : {std::pair{"R", &d.r}, {"G", &d.g}, {"B", &d.b}, {"A", &d.a}})
      channels.push_back(c);
  // OpenEXR's order: every slice set, the counts read, then the samples' storage given.
  std::vector<unsigned> counts(n);
  std::vector<std::vector<float*>> at(channels.size(), std::vector<float*>(n));
  Imf::DeepFrameBuffer frame;
  frame.insertSampleCountSlice(Imf::Slice(Imf::UINT, reinterpret_cast<char*>(counts.data()),
                                          sizeof(unsigned), sizeof(unsigned) * row));
  for (std::size_t c = 0; c < channels.size(); ++c)
    frame.insert(channels[c].first,
                 Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(at[c].data()), sizeof(float*),
                                sizeof(float*) * row, sizeof(float)));
  file.setFrameBuffer(frame);
  file.readPixelSampleCounts(window.min.y, window.max.y);
  for (std::size_t c = 0; c < channels.size(); ++c) {
    std::vector<std::vector<float>>& samples = *channels[c].second;
    samples.resize(n);
    for (std::size_t p = 0; p < n; ++p) {
      samples[p].resize(counts[p]);
      at[c][p] = samples[p].data();
    }
  }
  file.readPixels(window.min.y, window.max.y);
  return d;
}

}  // namespace voxspan::test
