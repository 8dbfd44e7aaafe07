#include "output_files.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetMeasure.h>
#include <png.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPolyData.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLPolyDataReader.h>

#include <algorithm>
#include <fstream>
#include <regex>
#include <map>
#include <sstream>

namespace voxspan::test {

double DecodedPng::fraction_unlike_row_background(int tolerance) const {
  if (width <= 0 || height <= 0) return 0;
  std::size_t unlike = 0;
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* row = &rgba[std::size_t(y) * std::size_t(width) * 4];
    std::map<std::uint32_t, int> counts;
    for (int x = 0; x < width; ++x)
      ++counts[std::uint32_t(row[4 * x]) | std::uint32_t(row[4 * x + 1]) << 8 |
               std::uint32_t(row[4 * x + 2]) << 16];
    const std::uint32_t mode =
        std::max_element(counts.begin(), counts.end(), [](const auto& a, const auto& b) {
          return a.second < b.second;
        })->first;
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c)
        if (std::abs(int(row[4 * x + c]) - int((mode >> (8 * c)) & 255)) > tolerance) {
          ++unlike;
          break;
        }
  }
  return double(unlike) / (double(width) * double(height));
}

DecodedPng read_png_file(const std::filesystem::path& path) {
  DecodedPng out;
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str())) {
    out.error = image.message;
    return out;
  }
  image.format = PNG_FORMAT_RGBA;
  out.width = int(image.width);
  out.height = int(image.height);
  out.rgba.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, out.rgba.data(), 0, nullptr)) {
    out.error = image.message;
    png_image_free(&image);
    return out;
  }
  out.ok = true;
  return out;
}

std::vector<std::string> read_lines(const std::filesystem::path& path, bool* complete) {
  std::ifstream in(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  if (complete) *complete = text.empty() || text.back() == '\n';
  std::vector<std::string> lines;
  std::istringstream s(text);
  for (std::string line; std::getline(s, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> files_in(const std::filesystem::path& folder) {
  std::vector<std::string> names;
  if (!std::filesystem::is_directory(folder)) return names;
  for (const auto& e : std::filesystem::directory_iterator(folder))
    if (e.is_regular_file()) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<std::string> temporaries_under(const std::filesystem::path& root) {
  std::vector<std::string> found;
  for (const auto& e : std::filesystem::recursive_directory_iterator(root))
    if (e.path().filename().string().find(".tmp.") != std::string::npos)
      found.push_back(e.path().string());
  return found;
}

VdbContents read_vdb(const std::filesystem::path& path) {
  VdbContents out;
  try {
    openvdb::initialize();
    openvdb::io::File file(path.string());
    file.open();
    openvdb::GridPtrVecPtr grids = file.getGrids();
    openvdb::MetaMap::Ptr meta = file.getMetadata();
    file.close();
    for (const auto& g : *grids) {
      out.grids.push_back(g->getName());
      if (g->getName() != "fluid") continue;
      out.fluid_class = g->getGridClass() == openvdb::GRID_LEVEL_SET ? "level set" : "other";
      // An empty level set (no fluid) has volume 0; OpenVDB's measure refuses it.
      if (auto f = openvdb::gridPtrCast<openvdb::FloatGrid>(g); f && f->activeVoxelCount() > 0)
        out.fluid_volume = openvdb::tools::levelSetVolume(*f);
    }
    if (auto step = meta->getMetadata<openvdb::Int64Metadata>("step")) out.step = step->value();
    out.ok = true;
  } catch (const std::exception& e) {
    out.error = e.what();
  }
  return out;
}

bool has_appended_data(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  return text.find("<AppendedData") != std::string::npos;
}

// The contents of a VTK XML file that `Reader` reads: `fill(contents, data set)`, and ok; only
// appended_data when the reader refuses the file or fails on it.
template <class Contents, class Reader, class Fill>
Contents read_vtk_xml(const std::filesystem::path& path, Fill fill) {
  Contents out;
  out.appended_data = has_appended_data(path);
  vtkNew<Reader> reader;
  if (!reader->CanReadFile(path.c_str())) return out;
  reader->SetFileName(path.c_str());
  reader->Update();
  auto* data = reader->GetOutput();
  if (data == nullptr || reader->GetErrorCode() != 0) return out;
  fill(out, *data);
  out.ok = true;
  return out;
}

VtpContents read_vtp(const std::filesystem::path& path) {
  return read_vtk_xml<VtpContents, vtkXMLPolyDataReader>(
      path, [](VtpContents& out, vtkPolyData& poly) {
        out.points = poly.GetNumberOfPoints();
        for (int i = 0; i < poly.GetPointData()->GetNumberOfArrays(); ++i)
          out.arrays.push_back(poly.GetPointData()->GetArrayName(i));
      });
}

VtiContents read_vti(const std::filesystem::path& path) {
  return read_vtk_xml<VtiContents, vtkXMLImageDataReader>(
      path, [](VtiContents& out, vtkImageData& image) {
        image.GetDimensions(out.dims);
        vtkDataArray* state = image.GetCellData()->GetArray("state");
        out.has_state = state != nullptr;
        if (state != nullptr)
          for (vtkIdType c = 0; c < state->GetNumberOfTuples(); ++c)
            out.states.push_back(int(state->GetComponent(c, 0)));
      });
}

std::vector<std::string> pvd_files(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  std::vector<std::string> files;
  const std::regex file_attribute("file=\"([^\"]+)\"");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), file_attribute);
       it != std::sregex_iterator(); ++it)
    files.push_back((*it)[1]);
  return files;
}

}  // namespace voxspan::test
