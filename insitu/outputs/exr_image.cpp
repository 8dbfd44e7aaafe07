#include "insitu/outputs/exr_image.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStdIO.h>

#include "insitu/outputs/atomic_file.h"
#include "voxspan/error.h"

namespace voxspan {

std::string encode_exr_channel(const FloatImage& image, const std::string& channel) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != 4 * std::size_t(image.width) * std::size_t(image.height))
    throw make_error("EXR image: ", image.width, "x", image.height, " with ", image.rgba.size(),
                     " floats is not an RGBA image");
  try {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    header.channels().insert(channel, Imf::Channel(Imf::FLOAT));
    Imf::FrameBuffer frame;
    // The r component of every RGBA pixel, rows top first.
    const std::size_t pixel = 4 * sizeof(float);
    frame.insert(
        channel,
        Imf::Slice(Imf::FLOAT, const_cast<char*>(reinterpret_cast<const char*>(image.rgba.data())),
                   pixel, pixel * std::size_t(image.width)));
    Imf::StdOSStream stream;
    {
      Imf::OutputFile file(stream, header);
      file.setFrameBuffer(frame);
      file.writePixels(image.height);
    }
    return stream.str();
  } catch (const std::exception& e) {
    throw make_error("OpenEXR could not encode the ", channel, " image: ", e.what());
  }
}

void write_exr_channel(const std::filesystem::path& path, const FloatImage& image,
                       const std::string& channel, bool sync) {
  write_file_atomically(path, encode_exr_channel(image, channel), sync);
}

}  // namespace voxspan
