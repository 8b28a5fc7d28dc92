// libFuzzer harness: maps and worlds. The first byte chooses what the rest is:
//  - even: an image (PGM, PNG or anything OpenCV decodes), read by ReadGrayImage as
//    `simulate --world FILE.png` does, and turned into a world;
//  - odd: a map_server YAML, then optionally "\n%%IMAGE%%\n" and the bytes of its image, which
//    is written beside the YAML as map.pgm and map.png (so `image: map.pgm` finds it); read by
//    ReadMap as `simulate --world FILE.yaml` does.
#include <cstdint>
#include <filesystem>
#include <string>

#include "gridslam/io/map_io.hpp"
#include "gridslam/simulation/world.hpp"

#include "fuzz_util.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace gridslam;
  if (size == 0) {
    return 0;
  }
  static const std::string dir = [] {
    const std::string d = fuzz::ScratchPath(".d");
    std::filesystem::create_directories(d);
    return d;
  }();
  const std::string rest = fuzz::AsString(data + 1, size - 1);
  if (data[0] % 2 == 0) {
    const std::string image_path = dir + "/world.img";
    fuzz::WriteScratch(image_path, data + 1, size - 1);
    const auto image = io::ReadGrayImage(image_path, 0.05);
    if (image.ok()) {
      (void)simulation::WorldFromGrayImage("fuzz", image.value());
    }
    return 0;
  }
  static const std::string kSeparator = "\n%%IMAGE%%\n";
  const std::size_t cut = rest.find(kSeparator);
  const std::string yaml = rest.substr(0, cut);
  const std::string image =
      cut == std::string::npos ? std::string() : rest.substr(cut + kSeparator.size());
  const auto bytes = [](const std::string& s) {
    return reinterpret_cast<const std::uint8_t*>(s.data());
  };
  fuzz::WriteScratch(dir + "/map.yaml", bytes(yaml), yaml.size());
  fuzz::WriteScratch(dir + "/map.pgm", bytes(image), image.size());
  fuzz::WriteScratch(dir + "/map.png", bytes(image), image.size());
  const auto map = io::ReadMap(dir + "/map.yaml");
  if (map.ok()) {
    (void)simulation::WorldFromOccupancy("fuzz", map.value());
  }
  return 0;
}
