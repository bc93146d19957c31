// The signaller's hand signals on their own: what following each means at a machine's controls, which
// machines can follow which, and the drawing of each fitting its panel.
#include "harbour/scene/HandSignals.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "support/ControlSpecs.h"

namespace harbour::scene {
namespace {

using test::axis;
using test::button;

const HandSignal& named(const char* name) {
  const int n = find_hand_signal(name);
  EXPECT_GE(n, 0) << name;
  return hand_signals()[static_cast<std::size_t>(n)];
}

// a crane's cab: hoist, trolley, a luffing boom, the emergency stop; a tractor's: pedals and steering
const ControlTable crane({axis("hoist"), axis("trolley"), axis("luff"), button("emergency_stop")});
const ControlTable tractor({axis("steer"), axis("throttle", 0.0, 1.0), axis("brake", 0.0, 1.0)});

Controls levers(double hoist, double trolley, double luff, double stop = 0.0) {
  Controls c;
  c.value[0] = hoist;
  c.value[1] = trolley;
  c.value[2] = luff;
  c.value[3] = stop;
  return c;
}

TEST(HandSignals, AMotionSignalIsFollowedByItsLeverMovedItsWayAndASlowlyOneByHalfALeverAtMost) {
  EXPECT_TRUE(follows(named("hoist"), crane, levers(0.3, 0, 0)));
  EXPECT_FALSE(follows(named("hoist"), crane, levers(-0.3, 0, 0)));  // the wrong way
  EXPECT_FALSE(follows(named("hoist"), crane, levers(0.05, 0, 0)));  // not yet moved
  EXPECT_TRUE(follows(named("lower"), crane, levers(-1.0, 0, 0)));
  EXPECT_TRUE(follows(named("hoist-slowly"), crane, levers(0.3, 0, 0)));
  EXPECT_FALSE(follows(named("hoist-slowly"), crane, levers(0.8, 0, 0)));  // full speed is not slowly
  EXPECT_TRUE(follows(named("trolley-in"), crane, levers(0, -0.5, 0)));
  EXPECT_TRUE(follows(named("boom-up"), crane, levers(0, 0, 0.4)));  // the boom's lever here is `luff`
  EXPECT_FALSE(follows(named("boom-down"), crane, levers(0, 0, 0.4)));
}

TEST(HandSignals, StopIsEveryMotionAtRestAndAnEmergencyStopAlsoItsButton) {
  EXPECT_TRUE(follows(named("stop"), crane, levers(0.02, -0.03, 0)));
  EXPECT_FALSE(follows(named("stop"), crane, levers(0, 0.2, 0)));       // the trolley still driven
  EXPECT_FALSE(follows(named("stop"), crane, levers(0, 0.2, 0, 1.0)));  // a stop is not the emergency stop
  EXPECT_TRUE(follows(named("emergency-stop"), crane, levers(0, 0.2, 0, 1.0)));
  EXPECT_TRUE(follows(named("emergency-stop"), crane, levers(0, 0, 0)));
  // a vehicle stops with its foot off the accelerator (the brake and steering are not motions it stops)
  Controls driving;
  driving.value[1] = 0.6;
  EXPECT_FALSE(follows(named("stop"), tractor, driving));
  driving.value[1] = 0.0;
  driving.value[2] = 1.0;
  driving.value[0] = 0.5;
  EXPECT_TRUE(follows(named("stop"), tractor, driving));
}

TEST(HandSignals, AMachineWithoutTheSignalsControlCannotBeAskedForIt) {
  EXPECT_EQ(why_not_for(named("hoist"), crane), "");
  EXPECT_EQ(why_not_for(named("boom-down"), crane), "");
  EXPECT_NE(why_not_for(named("slew-left"), crane).find("slew"), std::string::npos);
  EXPECT_NE(why_not_for(named("extend"), crane).find("telescope"), std::string::npos);
  EXPECT_NE(why_not_for(named("hoist"), tractor).find("hoist"), std::string::npos);
  EXPECT_EQ(why_not_for(named("stop"), tractor), "");  // its accelerator
  EXPECT_NE(why_not_for(named("stop"), ControlTable({axis("steer")})), "");
}

TEST(HandSignals, EachIsNamedOnceAndDrawnWithinItsPanel) {
  std::set<std::string> names;
  for (const HandSignal& s : hand_signals()) {
    EXPECT_TRUE(names.insert(std::string(s.name)).second) << s.name;
    EXPECT_EQ(find_hand_signal(s.name), static_cast<int>(names.size()) - 1);
    const std::vector<std::vector<double>> strokes = signal_strokes(s);
    EXPECT_GE(strokes.size(), 6u) << s.name;  // head, trunk, shoulders, legs, two arms
    for (const std::vector<double>& stroke : strokes) {
      ASSERT_EQ(stroke.size() % 2, 0u) << s.name;
      ASSERT_GE(stroke.size(), 4u) << s.name;
      for (std::size_t k = 0; k < stroke.size(); k += 2) {
        EXPECT_GE(stroke[k], -1.2) << s.name;
        EXPECT_LE(stroke[k], 1.2) << s.name;
        EXPECT_GE(stroke[k + 1], -0.4) << s.name;
        EXPECT_LE(stroke[k + 1], 1.95) << s.name;
      }
    }
  }
  EXPECT_EQ(find_hand_signal("wave"), -1);
}

}  // namespace
}  // namespace harbour::scene
