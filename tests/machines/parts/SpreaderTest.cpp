#include "harbour/machines/parts/Spreader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace harbour::sim {
namespace {

constexpr double kDt = 0.001;
constexpr std::array<bool, 4> kUp{false, false, false, false}, kDown{true, true, true, true};

// a spreader's frame on a body hanging in a world without gravity (only its shapes are looked at)
struct Rig {
  physics::PhysicsWorld world{{}};
  SpreaderSettings settings;
  physics::BodyId body = physics::kWorld;
  std::unique_ptr<Spreader> spreader;

  Rig() {
    physics::BoxSettings b;
    b.half_extents_m = {1.2, 6.0, 0.5};
    b.mass_kg = settings.mass_kg;
    b.pose.position = {0, 0, 20};
    body = world.add_box(b);
    spreader = std::make_unique<Spreader>(world, body, 0, 0, settings);
  }
  // steps until the frame stops telescoping (or `limit_s`), returning the time it took
  double run(const SpreaderSize* button, const std::array<bool, 4>& flippers, bool landed, double limit_s) {
    double t = 0.0;
    spreader->step(button, flippers, landed, kDt);
    for (t = kDt; spreader->state().telescoping && t < limit_s; t += kDt)
      spreader->step(nullptr, flippers, landed, kDt);
    return t;
  }
};

// ISO 668 box lengths and ISO 1161 casting centres: the frame at each setting is as long as the box, its
// twistlocks on the castings
TEST(Spreader, EachSettingIsTheBoxsLengthWithItsTwistlocksOnTheCastings) {
  Rig rig;
  const std::vector<std::pair<SpreaderSize, std::pair<double, double>>> boxes = {
      {SpreaderSize::k20ft, {6.058, 5.853}},
      {SpreaderSize::k40ft, {12.192, 11.985}},
      {SpreaderSize::k45ft, {13.716, 13.509}}};
  for (const auto& [size, iso] : boxes) {
    rig.run(&size, kUp, false, 60.0);
    EXPECT_EQ(rig.spreader->state().size, size);
    EXPECT_NEAR(rig.spreader->state().length_m, iso.first, 1e-9) << size_ft(size);
    EXPECT_NEAR(2.0 * rig.spreader->pin_half_length_m(), iso.second, 1e-9) << size_ft(size);
    EXPECT_NEAR(2.0 * rig.spreader->pin_half_width_m(), 2.259, 1e-12);
    EXPECT_NEAR(2.0 * rig.spreader->half_extents_m().x, 2.438, 1e-12);
  }
}

// Each end moves at the telescope's speed: 40 -> 20 ft moves each end (11.985 - 5.853) / 2 m at 0.2 m/s,
// 15.33 s; 20 -> 45 ft 19.14 s
TEST(Spreader, TelescopesAtItsSpeedAndNotWhileLandedOrLocked) {
  Rig rig;
  const SpreaderSize to20 = SpreaderSize::k20ft, to45 = SpreaderSize::k45ft;
  // landed: the button changes the setting, but the frame keeps its length
  rig.spreader->step(&to20, kUp, true, kDt);
  for (int k = 0; k < 5000; ++k)
    rig.spreader->step(nullptr, kUp, true, kDt);
  EXPECT_TRUE(rig.spreader->state().telescoping);
  // (its ends' overhang beyond the twistlocks is already the new setting's: 1 mm shorter each at 20 ft)
  EXPECT_NEAR(rig.spreader->state().length_m, 12.192, 2e-3 + 1e-9);
  EXPECT_NEAR(2.0 * rig.spreader->pin_half_length_m(), 11.985, 1e-12);
  // lifted off: it telescopes, each end at the set speed
  const double shrink_s = rig.run(nullptr, kUp, false, 60.0);
  EXPECT_NEAR(shrink_s, (11.985 - 5.853) / 2 / 0.2, 2 * kDt);
  EXPECT_FALSE(rig.spreader->state().telescoping);
  const double grow_s = rig.run(&to45, kUp, false, 60.0);
  EXPECT_NEAR(grow_s, (13.509 - 5.853) / 2 / 0.2, 2 * kDt);
  EXPECT_NEAR(rig.spreader->state().length_m, 13.716, 1e-9);
}

// A flipper swings down in flipper_time_s and up again in the same time; the four are independent
TEST(Spreader, FlippersSwingInTheirTimeEachOnItsOwn) {
  Rig rig;
  const std::array<bool, 4> two{true, false, true, false};
  for (int k = 0; k < 1500; ++k)
    rig.spreader->step(nullptr, two, false, kDt);
  std::array<double, 4> f = rig.spreader->state().flippers;
  EXPECT_NEAR(f[0], 0.5, 1e-9);
  EXPECT_NEAR(f[2], 0.5, 1e-9);
  EXPECT_EQ(f[1], 0.0);
  EXPECT_EQ(f[3], 0.0);
  for (int k = 0; k < 1500; ++k)
    rig.spreader->step(nullptr, two, false, kDt);
  f = rig.spreader->state().flippers;
  EXPECT_NEAR(f[0], 1.0, 1e-9);
  EXPECT_NEAR(f[2], 1.0, 1e-9);
  for (int k = 0; k < 3000; ++k)
    rig.spreader->step(nullptr, kUp, false, kDt);
  EXPECT_EQ(rig.spreader->state().flippers, (std::array<double, 4>{0, 0, 0, 0}));
}

// A keyframe mid-telescope with flippers half down continues exactly as the run it was taken from
TEST(Spreader, AKeyframeMidTelescopeContinuesExactly) {
  Rig a, b;
  const SpreaderSize to20 = SpreaderSize::k20ft;
  a.spreader->step(&to20, kDown, false, kDt);
  for (int k = 0; k < 4000; ++k)
    a.spreader->step(nullptr, kDown, false, kDt);
  core::StateWriter out;
  a.spreader->save_state(out);
  core::StateReader in(out.bytes());
  b.spreader->restore_state(in);
  for (int k = 0; k < 6000; ++k) {
    a.spreader->step(nullptr, kDown, false, kDt);
    b.spreader->step(nullptr, kDown, false, kDt);
  }
  EXPECT_EQ(a.spreader->state().size, b.spreader->state().size);
  EXPECT_EQ(a.spreader->state().length_m, b.spreader->state().length_m);
  EXPECT_EQ(a.spreader->state().flippers, b.spreader->state().flippers);
  EXPECT_EQ(a.spreader->state().telescoping, b.spreader->state().telescoping);
}

}  // namespace
}  // namespace harbour::sim
