// tests/support/depth_exr_reader.h - a flat scanline OpenEXR depth image read with OpenEXR's own
// reader (tests only): its channel names and channel Z, per pixel, row 0 at the top.
#pragma once

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace voxspan::test {

struct DepthExr {
  int width = 0, height = 0;
  std::vector<std::string> channels;
  std::vector<float> z;  // row 0 at the top
};

inline DepthExr read_depth_exr(const std::filesystem::path& path) {
  Imf::InputFile file(path.c_str());
  const Imath::Box2i window = file.header().dataWindow();
  DepthExr d;
  d.width = window.max.x - window.min.x + 1;
  d.height = window.max.y - window.min.y + 1;
  for (auto c = file.header().channels().begin(); c != file.header().channels().end(); ++c)
    d.channels.push_back(c.name());
  d.z.assign(std::size_t(d.width) * std::size_t(d.height), -1.0f);
  Imf::FrameBuffer frame;
  frame.insert("Z", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(d.z.data()), sizeof(float),
                               sizeof(float) * std::size_t(d.width)));
  file.setFrameBuffer(frame);
  file.readPixels(window.min.y, window.max.y);
  return d;
}

}  // namespace voxspan::test
