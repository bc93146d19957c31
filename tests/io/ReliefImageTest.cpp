#include "harbour/io/ReliefImage.h"

#include <gtest/gtest.h>
#include <png.h>

#include <cstdio>
#include <filesystem>
#include <vector>

#include "harbour/bulk/BulkWorld.h"

namespace harbour::io {
namespace {

TEST(ReliefImage, WritesAPngWithTheGridsSideBySide) {
  bulk::Material m{"coal", 960, 0.6, 0.5, 1.0};
  bulk::BulkWorld world(m, {});
  const int a = world.add_grid({100, 80, 0.1}, {});
  const int b = world.add_grid({50, 50, 0.1}, {});
  world.add_heap(a, 5.0, 4.0, 3.0);
  const std::string path = (std::filesystem::temp_directory_path() / "relief_test.png").string();
  const bulk::HeightGrid* grids[] = {&world.grid(a), &world.grid(b)};
  write_relief_png(path, grids);

  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  ASSERT_TRUE(png_image_begin_read_from_file(&image, path.c_str()));
  EXPECT_EQ(image.width, 100u + 6u + 50u);
  EXPECT_EQ(image.height, 80u);
  image.format = PNG_FORMAT_RGB;
  std::vector<unsigned char> pixels(PNG_IMAGE_SIZE(image));
  ASSERT_TRUE(png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr));
  auto pixel = [&](int x, int y) { return &pixels[(static_cast<std::size_t>(y) * image.width + x) * 3]; };
  // the heap is coloured, the bare floor grey, and the heap's lit and shaded flanks differ
  EXPECT_NE(pixel(50, 40)[0], pixel(2, 2)[0]);
  EXPECT_NE(pixel(40, 30)[0], pixel(60, 50)[0]);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace harbour::io
