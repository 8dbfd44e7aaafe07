// tests/support/deep_exr_reader.h - a deep scanline OpenEXR file read with OpenEXR's own reader
// (tests only): per pixel, row 0 at the top, the samples of channels Z and ZBack.
#pragma once

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDeepFrameBuffer.h>
#include <OpenEXR/ImfDeepScanLineInputFile.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfPartType.h>

#include <filesystem>
#include <string>
#include <vector>

namespace voxspan::test {

struct DeepExr {
  std::string type;  // the header's part type: "deepscanline"
  int width = 0, height = 0;
  bool has_z = false, has_z_back = false;
  std::vector<std::vector<float>> z, z_back;  // per pixel, its samples
};

inline DeepExr read_deep_exr(const std::filesystem::path& path) {
  Imf::DeepScanLineInputFile file(path.c_str());
  DeepExr d;
  d.type = file.header().type();
  const Imath::Box2i window = file.header().dataWindow();
  d.width = window.max.x - window.min.x + 1;
  d.height = window.max.y - window.min.y + 1;
  d.has_z = file.header().channels().findChannel("Z") != nullptr;
  d.has_z_back = file.header().channels().findChannel("ZBack") != nullptr;
  const std::size_t n = std::size_t(d.width) * std::size_t(d.height);
  // OpenEXR's order: every slice set, the counts read, then the samples' storage given.
  std::vector<unsigned> counts(n);
  std::vector<float*> z_at(n), z_back_at(n);
  const std::size_t row = std::size_t(d.width);
  Imf::DeepFrameBuffer frame;
  frame.insertSampleCountSlice(Imf::Slice(Imf::UINT, reinterpret_cast<char*>(counts.data()),
                                          sizeof(unsigned), sizeof(unsigned) * row));
  frame.insert("Z", Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(z_at.data()), sizeof(float*),
                                   sizeof(float*) * row, sizeof(float)));
  frame.insert("ZBack", Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(z_back_at.data()),
                                       sizeof(float*), sizeof(float*) * row, sizeof(float)));
  file.setFrameBuffer(frame);
  file.readPixelSampleCounts(window.min.y, window.max.y);
  d.z.resize(n);
  d.z_back.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    d.z[p].resize(counts[p]);
    d.z_back[p].resize(counts[p]);
    z_at[p] = d.z[p].data();
    z_back_at[p] = d.z_back[p].data();
  }
  file.readPixels(window.min.y, window.max.y);
  return d;
}

}  // namespace voxspan::test
