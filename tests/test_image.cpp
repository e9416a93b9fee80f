// Images and PNG files: pixels survive a round trip, writes are atomic, failures name the path.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "plumage/error.hpp"
#include "plumage/image.hpp"

using namespace plumage;
namespace fs = std::filesystem;

namespace {

fs::path fresh_folder(const std::string& name) {
  static int counter = 0;
  const fs::path p = fs::temp_directory_path() /
                     ("plumage-image-" + name + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

std::size_t entries(const fs::path& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}

Image test_pattern(int w, int h) {
  Image im(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      im.at(x, y) = Rgb8{static_cast<std::uint8_t>(x * 7 + y), static_cast<std::uint8_t>(y * 11),
                         static_cast<std::uint8_t>((x * y) ^ 0x5a)};
  return im;
}

}  // namespace

TEST_CASE("images hold pixels and clip rectangles", "[image]") {
  Image im(5, 4, Rgb8{1, 2, 3});
  CHECK(im.width() == 5);
  CHECK(im.height() == 4);
  CHECK(im.pixels().size() == 20);
  CHECK(im.at(4, 3) == Rgb8{1, 2, 3});
  CHECK_THROWS_WITH(im.at(5, 0), Catch::Contains("(5, 0) outside a 5x4 image"));
  CHECK_THROWS_AS(Image(-1, 3), Error);

  im.fill_rect(3, -2, 100, 4, Rgb8{9, 9, 9});  // clipped to x 3..4, y 0..1
  CHECK(im.at(3, 0) == Rgb8{9, 9, 9});
  CHECK(im.at(4, 1) == Rgb8{9, 9, 9});
  CHECK(im.at(2, 0) == Rgb8{1, 2, 3});
  CHECK(im.at(3, 2) == Rgb8{1, 2, 3});
  im.fill_rect(-10, -10, 5, 5, Rgb8{7, 7, 7});  // entirely outside: nothing
  CHECK(im.at(0, 0) == Rgb8{1, 2, 3});
}

TEST_CASE("linear images become display sRGB", "[image]") {
  LinearImage lin(2, 1);
  lin.at(0, 0) = RgbF{0.5f, 0.0f, 1.0f};
  lin.at(1, 0) = RgbF{-0.2f, 2.0f, 0.18f};
  const Image out = to_display(lin);
  CHECK(out.at(0, 0) == Rgb8{188, 0, 255});
  CHECK(out.at(1, 0) == Rgb8{0, 255, 118});
}

TEST_CASE("PNG round trip keeps every pixel", "[image]") {
  const fs::path dir = fresh_folder("roundtrip");
  const fs::path file = dir / "sub" / "pattern.png";  // missing parent folders are created
  const Image im = test_pattern(37, 23);
  write_png(im, file);
  {
    std::ifstream in(file, std::ios::binary);
    char signature[8] = {};
    in.read(signature, 8);
    CHECK(std::string(signature + 1, 3) == "PNG");
  }
  const Image back = read_png(file);
  REQUIRE(back.width() == 37);
  REQUIRE(back.height() == 23);
  CHECK(std::equal(back.pixels().begin(), back.pixels().end(), im.pixels().begin()));

  // Overwriting replaces the file whole, leaving no temporary beside it.
  write_png(Image(2, 3, Rgb8{10, 20, 30}), file);
  const Image again = read_png(file);
  CHECK(again.width() == 2);
  CHECK(again.at(1, 2) == Rgb8{10, 20, 30});
  CHECK(entries(file.parent_path()) == 1);
  fs::remove_all(dir);
}

TEST_CASE("failed PNG writes name the path and leave nothing behind", "[image]") {
  const fs::path dir = fresh_folder("fail");
  const Image im = test_pattern(4, 4);

  // Parent "folder" is a regular file: the folder cannot exist.
  std::ofstream(dir / "plain") << "x";
  const fs::path under_file = dir / "plain" / "out.png";
  CHECK_THROWS_WITH(write_png(im, under_file), Catch::Contains(under_file.string()));
  CHECK(entries(dir) == 1);

  // The target is a folder: refused before anything is written (plumage/atomic_file.hpp).
  fs::create_directories(dir / "occupied.png" / "inside");
  CHECK_THROWS_WITH(write_png(im, dir / "occupied.png"), Catch::Contains("occupied.png"));
  CHECK(entries(dir) == 2);
  CHECK(fs::is_directory(dir / "occupied.png"));

  // An unwritable folder (permissions do not bind root, so only checked for other users).
  if (::geteuid() != 0) {
    fs::create_directories(dir / "locked");
    fs::permissions(dir / "locked", fs::perms::owner_read | fs::perms::owner_exec);
    CHECK_THROWS_WITH(write_png(im, dir / "locked" / "out.png"), Catch::Contains("locked/out.png"));
    CHECK(entries(dir / "locked") == 0);
    fs::permissions(dir / "locked", fs::perms::owner_all);
  }

  CHECK_THROWS_WITH(write_png(Image(), dir / "empty.png"), Catch::Contains("empty.png"));
  CHECK_FALSE(fs::exists(dir / "empty.png"));
  fs::remove_all(dir);
}

TEST_CASE("reading a file that is not a PNG names it", "[image]") {
  const fs::path dir = fresh_folder("notpng");
  std::ofstream(dir / "fake.png") << "not a png at all";
  CHECK_THROWS_WITH(read_png(dir / "fake.png"), Catch::Contains("fake.png: cannot read PNG"));
  CHECK_THROWS_WITH(read_png(dir / "missing.png"), Catch::Contains("missing.png"));
  fs::remove_all(dir);
}
