// The trainee's window on a real X server (Xvfb, 1600x900): it opens fitting the screen, shows the whole
// picture scaled as it is resized (its HUD's corner and its middle where they belong), and the mouse moved
// to its edge changes no control with the shipped keyboard.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "harbour/machines/sts/StsCrane.h"
#include "harbour/station/DeviceInput.h"
#include "harbour/station/DeviceMappingFile.h"
#include "harbour/station/StationWindow.h"
#include "scenes/StsScenes.h"

namespace harbour::station {
namespace {

struct Xvfb {
  pid_t pid = -1;
  explicit Xvfb(const std::string& display) {
    pid = fork();
    if (pid == 0) {
      execlp("Xvfb", "Xvfb", display.c_str(), "-screen", "0", "1600x900x24", "-nolisten", "tcp",
             static_cast<char*>(nullptr));
      _exit(127);
    }
    setenv("DISPLAY", display.c_str(), 1);
    std::this_thread::sleep_for(std::chrono::seconds(1));
  }
  ~Xvfb() {
    kill(pid, SIGTERM);
    waitpid(pid, nullptr, 0);
  }
};

// the colour at (x, y) of an RGB picture, top row first
std::array<int, 3> at(const std::vector<std::uint8_t>& rgb, int width, int x, int y) {
  const std::size_t k = 3 * (static_cast<std::size_t>(y) * width + x);
  return {rgb[k], rgb[k + 1], rgb[k + 2]};
}

TEST(StationWindow, FitsTheScreenKeepsTheWholePictureResizedAndTheMouseMovesNoControl) {
  if (std::system("command -v Xvfb > /dev/null") != 0) GTEST_SKIP() << "Xvfb is not installed";
  const Xvfb server(":" + std::to_string(150 + getpid() % 50));
  StationWindow window(1920, 1080, "harboursim: test");
  int w = 0, h = 0;
  window.size(w, h);
  EXPECT_LE(w, 1600);
  EXPECT_LE(h, 900);
  EXPECT_NEAR(static_cast<double>(w) / h, 1920.0 / 1080.0, 0.02);
  // a picture: blue, a red block in the HUD's corner (top left), a green square in the middle
  constexpr int kW = 1920, kH = 1080;
  std::vector<unsigned char> picture(3 * kW * kH);
  for (int y = 0; y < kH; ++y)  // bottom row first, as OpenGL reads it
    for (int x = 0; x < kW; ++x) {
      const int top_y = kH - 1 - y;
      unsigned char* p = &picture[3 * (static_cast<std::size_t>(y) * kW + x)];
      const bool hud = x < 300 && top_y < 60,
                 middle = std::abs(x - kW / 2) < 200 && std::abs(top_y - kH / 2) < 200;
      p[0] = hud ? 220 : 0;
      p[1] = middle ? 220 : 0;
      p[2] = hud || middle ? 0 : 200;
    }
  for (const auto& [width, height] : {std::pair{1280, 720}, std::pair{1600, 900}}) {
    window.resize(width, height);
    window.hand_over(picture.data(), kW, kH, 3, 3 * kW);
    for (int n = 0; n < 10; ++n) {
      window.pump();
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    int sw = 0, sh = 0;
    const std::vector<std::uint8_t> shown = window.shown(sw, sh);
    SCOPED_TRACE(std::to_string(sw) + "x" + std::to_string(sh));
    EXPECT_EQ(sw, width);
    EXPECT_EQ(sh, height);
    const double scale = static_cast<double>(sw) / kW;
    const auto hud = at(shown, sw, static_cast<int>(100 * scale), static_cast<int>(30 * scale));
    const auto middle = at(shown, sw, sw / 2, sh / 2);
    const auto corner = at(shown, sw, sw - 5, sh - 5);
    EXPECT_GT(hud[0], 150);
    EXPECT_LT(hud[2], 60);
    EXPECT_GT(middle[1], 150);
    EXPECT_GT(corner[2], 150);  // the picture's far corner is in the window too
  }
  // the keyboard mapping binds no mouse: the pointer at the window's edge drives nothing
  const scene::ControlTable table = scenes::sts_controls();
  DeviceInput input(table,
                    load_device_mapping(std::string(HARBOUR_DATA_DIR) + "/devices/keyboard.yaml", table));
  for (const auto& [x, y] : {std::pair{0, 0}, std::pair{1599, 450}, std::pair{800, 899}}) {
    window.move_mouse(x, y);
    window.pump();
    const scene::Controls c = input.sample();
    EXPECT_TRUE(c == table.neutral()) << "the pointer at " << x << "," << y << " moved a control";
  }
}

}  // namespace
}  // namespace harbour::station
