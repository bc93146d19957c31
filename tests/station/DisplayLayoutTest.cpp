// Where the image generator's pictures go: the windows of a profile, the tiles and eyes in them, and the
// copy of a picture into its tile.
#include "harbour/station/DisplayLayout.h"

#include <gtest/gtest.h>

#include <string>

namespace harbour::station {
namespace {

Profile cabin(int displays) {
  Profile p;
  for (int n = 0; n < displays; ++n) {
    DisplayChannel c;
    c.name = "d" + std::to_string(n);
    c.width = 1920;
    c.height = 1200;
    p.displays.push_back(c);
  }
  return p;
}

TEST(DisplayLayout, ChannelsShareAWindowOrHaveOneEach) {
  Profile p = cabin(4);
  DisplayLayout shared = layout_displays(p);
  ASSERT_EQ(shared.windows.size(), 1u);
  EXPECT_EQ(shared.windows[0].width, 1920);
  EXPECT_EQ(shared.windows[0].height, 300);  // each channel keeps its aspect ratio
  EXPECT_EQ(shared.render_width, 480);
  ASSERT_EQ(shared.pictures.size(), 4u);
  EXPECT_EQ(shared.pictures[3].x0, 1440);
  EXPECT_EQ(shared.pictures[3].window, 0);
  p.windows = Profile::Windows::kPerDisplay;
  const DisplayLayout apart = layout_displays(p);
  ASSERT_EQ(apart.windows.size(), 4u);
  for (int n = 0; n < 4; ++n) {
    EXPECT_EQ(apart.windows[static_cast<std::size_t>(n)].width, 480);
    EXPECT_EQ(apart.windows[static_cast<std::size_t>(n)].display, n);
    EXPECT_EQ(apart.pictures[static_cast<std::size_t>(n)].window, n);
    EXPECT_EQ(apart.pictures[static_cast<std::size_t>(n)].x0, 0);
  }
}

// A cabin whose projectors have hosts of their own: the station draws none of them, a channel its one (the
// first display's HUD stays with it)
TEST(DisplayLayout, RemoteDisplaysAreLeftToTheirChannels) {
  const Profile p = load_profile(std::string(HARBOUR_DATA_DIR) + "/profiles/immersive_remote.yaml");
  ASSERT_EQ(p.displays.size(), 4u);
  for (const DisplayChannel& d : p.displays)
    EXPECT_TRUE(d.remote) << d.name;
  EXPECT_TRUE(p.displays[0].hud);
  EXPECT_FALSE(p.displays[1].hud);
  const Profile own = with_displays(p, [](const DisplayChannel& d) { return !d.remote; });
  EXPECT_TRUE(own.displays.empty());
  const DisplayLayout none = layout_displays(own);
  EXPECT_TRUE(none.windows.empty());
  EXPECT_TRUE(none.pictures.empty());
  const Profile floor = with_displays(p, [](const DisplayChannel& d) { return d.name == "floor"; });
  ASSERT_EQ(floor.displays.size(), 1u);
  EXPECT_FALSE(floor.displays[0].remote);  // drawn where it is now
  ASSERT_TRUE(floor.displays[0].frustum_rad.has_value());
  EXPECT_EQ(layout_displays(floor).pictures.size(), 1u);
  // the shipped immersive profile draws every display itself
  for (const DisplayChannel& d :
       load_profile(std::string(HARBOUR_DATA_DIR) + "/profiles/immersive.yaml").displays)
    EXPECT_FALSE(d.remote) << d.name;
}

TEST(DisplayLayout, StereoDrawsTwoEyesPerChannel) {
  Profile p = cabin(1);
  p.stereo = Profile::Stereo{Profile::Stereo::Mode::kSideBySide, 0.064, 3.0};
  const DisplayLayout halves = layout_displays(p);
  EXPECT_EQ(halves.render_width, 960);  // each eye half the width, stretched back by the display
  ASSERT_EQ(halves.pictures.size(), 2u);
  EXPECT_DOUBLE_EQ(halves.pictures[0].eye_offset_m, -0.032);
  EXPECT_DOUBLE_EQ(halves.pictures[1].eye_offset_m, 0.032);
  EXPECT_EQ(halves.pictures[0].x0, 0);
  EXPECT_EQ(halves.pictures[1].x0, 960);
  EXPECT_DOUBLE_EQ(halves.pictures[1].pixel_aspect, 2.0);
  p.stereo->mode = Profile::Stereo::Mode::kAnaglyph;
  const DisplayLayout glasses = layout_displays(p);
  EXPECT_EQ(glasses.render_width, 1920);
  ASSERT_EQ(glasses.pictures.size(), 2u);
  EXPECT_EQ(glasses.pictures[0].colours, 0b100);  // red: the left eye
  EXPECT_EQ(glasses.pictures[1].colours, 0b011);  // cyan: the right
  EXPECT_EQ(glasses.pictures[1].x0, 0);
}

TEST(DisplayLayout, APictureLandsInItsTileTurnedUpright) {
  // a 2 x 2 RGBA picture, bottom row first: bottom (10, 20), top (30, 40) in red
  const unsigned char pixels[16] = {10, 1, 2, 255, 20, 1, 2, 255, 30, 3, 4, 255, 40, 3, 4, 255};
  std::vector<std::uint8_t> frame(4 * 2 * 3, 0);
  ASSERT_TRUE(copy_picture(frame, 4, 2, pixels, 2, 2, 4, 8, 2, 0b111));
  EXPECT_EQ(frame[3 * 2], 30);  // top row, column 2
  EXPECT_EQ(frame[3 * 3], 40);
  EXPECT_EQ(frame[12 + 3 * 2], 10);  // bottom row
  EXPECT_EQ(frame[12 + 3 * 2 + 1], 1);
  EXPECT_EQ(frame[0], 0);  // the other tile untouched
  // only green and blue (the right eye of an anaglyph): red stays as the left eye left it
  const unsigned char cyan[12] = {99, 7, 8, 99, 7, 8, 99, 7, 8, 99, 7, 8};
  ASSERT_TRUE(copy_picture(frame, 4, 2, cyan, 2, 2, 3, 6, 2, 0b011));
  EXPECT_EQ(frame[3 * 2], 30);
  EXPECT_EQ(frame[3 * 2 + 1], 7);
  EXPECT_EQ(frame[3 * 2 + 2], 8);
  // a picture that does not fit writes nothing
  const std::vector<std::uint8_t> before = frame;
  EXPECT_FALSE(copy_picture(frame, 4, 2, pixels, 2, 2, 4, 8, 3, 0b111));
  EXPECT_FALSE(copy_picture(frame, 4, 2, pixels, 2, 3, 4, 8, 0, 0b111));
  EXPECT_FALSE(copy_picture(frame, 4, 2, pixels, 2, 2, 2, 8, 0, 0b111));
  EXPECT_EQ(frame, before);
}

}  // namespace
}  // namespace harbour::station
