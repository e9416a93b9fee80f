// OpenEXR writer (exr.hpp): encoded into memory, then written atomically (atomic_file.hpp).
#include "plumage/exr.hpp"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <cstdio>
#include <ostream>

#include "plumage/atomic_file.hpp"
#include "plumage/error.hpp"

namespace plumage {

std::string spectral_channel_name(const SpectralChannels& s, int bin) {
  const double width = (s.lambda_max_nm - s.lambda_min_nm) / s.bins;
  char name[64];
  std::snprintf(name, sizeof name, "S%02d.%g-%gnm", bin, s.lambda_min_nm + width * bin,
                s.lambda_min_nm + width * (bin + 1));
  return name;
}

void write_exr(const LinearImage& rgb, const std::filesystem::path& path, const SpectralChannels* spectral,
               const std::map<std::string, std::string>& attributes) {
  const int w = rgb.width(), h = rgb.height();
  if (w <= 0 || h <= 0) throw Error(path.string() + ": cannot write an empty image as OpenEXR");
  const int bins = spectral != nullptr ? spectral->bins : 0;
  if (bins > 0 && spectral->values.size() != static_cast<std::size_t>(w) * h * bins) {
    throw Error(path.string() + ": spectral buffer has " + std::to_string(spectral->values.size()) +
                " values, expected width × height × bins = " + std::to_string(std::size_t(w) * h * bins));
  }
  try {
    Imf::Header header(w, h);
    header.compression() = Imf::ZIP_COMPRESSION;
    for (const auto& [name, value] : attributes) header.insert(name, Imf::StringAttribute(value));
    Imf::FrameBuffer fb;
    const std::size_t px = sizeof(RgbF);
    char* base = const_cast<char*>(reinterpret_cast<const char*>(rgb.pixels().data()));
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
      header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
      fb.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), px, px * w));
    }
    if (bins > 0) {
      char* sbase = const_cast<char*>(reinterpret_cast<const char*>(spectral->values.data()));
      for (int b = 0; b < bins; ++b) {
        const std::string name = spectral_channel_name(*spectral, b);
        header.channels().insert(name, Imf::Channel(Imf::FLOAT));
        fb.insert(name, Imf::Slice(Imf::FLOAT, sbase + b * sizeof(float), sizeof(float) * bins,
                                   sizeof(float) * bins * w));
      }
    }
    Imf::StdOSStream stream;
    {
      Imf::OutputFile file(stream, header);
      file.setFrameBuffer(fb);
      file.writePixels(h);
    }
    const std::string bytes = stream.str();
    write_file_atomically(
        path, [&](std::ostream& out) { out.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); },
        /*binary=*/true);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(path.string() + ": cannot write OpenEXR (" + e.what() + ")");
  }
}

LinearImage read_exr_rgb(const std::filesystem::path& path) {
  try {
    Imf::InputFile file(path.string().c_str());
    const auto dw = file.header().dataWindow();
    const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
    LinearImage img(w, h);
    char* base = reinterpret_cast<char*>(img.pixels().data());
    const std::size_t px = sizeof(RgbF);
    // The frame buffer is addressed by absolute data-window coordinates.
    base -= (static_cast<std::ptrdiff_t>(dw.min.x) + static_cast<std::ptrdiff_t>(dw.min.y) * w) *
            static_cast<std::ptrdiff_t>(px);
    Imf::FrameBuffer fb;
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) fb.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), px, px * w));
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    return img;
  } catch (const std::exception& e) {
    throw Error(path.string() + ": cannot read OpenEXR (" + e.what() + ")");
  }
}

std::map<std::string, std::string> read_exr_string_attributes(const std::filesystem::path& path) {
  try {
    Imf::InputFile file(path.string().c_str());
    std::map<std::string, std::string> out;
    for (auto it = file.header().begin(); it != file.header().end(); ++it) {
      if (const auto* a = dynamic_cast<const Imf::StringAttribute*>(&it.attribute())) out[it.name()] = a->value();
    }
    return out;
  } catch (const std::exception& e) {
    throw Error(path.string() + ": cannot read OpenEXR (" + e.what() + ")");
  }
}

}  // namespace plumage
