// A remote channel draws what the station's own image generator would: a snapshot and the bulk material sent
// as a frame and tiles (what goes over the network) come back field for field, and the two pictures drawn
// from them agree pixel for pixel but for float rounding.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>

#include <osg/Image>

#include "harbour/bulk/BulkPublish.h"
#include "harbour/ig/ImageGenerator.h"
#include "harbour/io/ExerciseFiles.h"
#include "harbour/machines/MachineRegistry.h"
#include "harbour/net/SceneMessages.h"
#include "harbour/sim/Pilot.h"

namespace harbour::net {
namespace {

constexpr int kWidth = 320, kHeight = 180;

struct Sent {
  scene::SceneDescription scene;
  std::unique_ptr<scene::Snapshot> snapshot = std::make_unique<scene::Snapshot>();
  scene::BulkView bulk;
};

// An exercise run `seconds` under its scripted operator: its scene, snapshot and bulk material then
Sent run(const std::string& name, double seconds) {
  const sim::ExerciseSettings exercise =
      io::load_exercise(std::string(HARBOUR_DATA_DIR) + "/exercises/" + name + ".yaml");
  sim::Simulation simulation(exercise.scenario);
  const std::unique_ptr<sim::Pilot> pilot = sim::make_pilot(exercise);
  while (simulation.time_s() < seconds)
    simulation.step(pilot->next(simulation));
  Sent sent;
  sent.scene = simulation.scene();
  simulation.write_snapshot(*sent.snapshot);
  if (simulation.bulk()) bulk::publish(*simulation.bulk(), sent.bulk);
  return sent;
}

// What a channel has after the frame and the tiles: the snapshot and the bulk material
struct Received {
  std::unique_ptr<scene::Snapshot> snapshot = std::make_unique<scene::Snapshot>();
  scene::BulkView bulk;
  int tiles = 0;
};
Received send(const Sent& sent) {
  Received got;
  std::vector<std::vector<std::uint32_t>> versions;
  changed_bulk_tiles(sent.bulk, 1, versions, [&](const ChannelBulkTile& tile) {
    EXPECT_TRUE(apply_bulk_tile(tile, got.bulk));
    ++got.tiles;
  });
  read_channel_frame(channel_frame(*sent.snapshot, &sent.bulk, 1), *got.snapshot, &got.bulk);
  return got;
}

double distance(const core::Vec3& a, const core::Vec3& b) {
  return core::length(a - b);
}

// the largest difference between two rotations' matrix entries
double rotation_difference(const core::Mat3& a, const core::Mat3& b) {
  double most = 0.0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      most = std::max(most, std::abs(a.m[r][c] - b.m[r][c]));
  return most;
}

// The share of pixels whose colours differ by more than `levels` (of 255)
double share_differing(const osg::Image& a, const osg::Image& b, int levels) {
  long differing = 0;
  for (int y = 0; y < a.t(); ++y)
    for (int x = 0; x < a.s(); ++x)
      for (int c = 0; c < 3; ++c)
        if (std::abs(static_cast<int>(a.data(x, y)[c]) - static_cast<int>(b.data(x, y)[c])) > levels) {
          ++differing;
          break;
        }
  return static_cast<double>(differing) / (a.s() * a.t());
}

TEST(ChannelFrame, CarriesEveryFieldTheImageGeneratorReads) {
  Sent sent = run("mhc_coal_discharge", 25.0);
  scene::Snapshot& s = *sent.snapshot;
  s.hand_signal = 4;
  s.hand_signal_at_s = 24.5;
  s.held = s.emergency_stop = s.awaiting_zero = true;
  s.cab.head_offset_m = {0.05, -0.02, 0.01};
  s.cab.look_yaw_rad = 0.3;
  ASSERT_FALSE(sent.bulk.grids.empty());
  const Received got = send(sent);
  const scene::Snapshot& r = *got.snapshot;
  EXPECT_EQ(r.time_s, s.time_s);
  EXPECT_EQ(r.hand_signal, 4);
  EXPECT_EQ(r.hand_signal_at_s, 24.5);
  EXPECT_TRUE(r.held && r.emergency_stop && r.awaiting_zero && !r.power_off && !r.diverged);
  EXPECT_EQ(r.time_of_day_h, s.time_of_day_h);
  EXPECT_EQ(r.visibility_m, s.visibility_m);
  EXPECT_EQ(r.day_of_year, s.day_of_year);
  EXPECT_EQ(r.latitude_deg, s.latitude_deg);
  EXPECT_EQ(r.sea.swell_count, s.sea.swell_count);
  EXPECT_LT(distance(r.cab.pose.position, s.cab.pose.position), 1e-9);
  EXPECT_LT(rotation_difference(r.cab.pose.rotation, s.cab.pose.rotation), 1e-9);
  EXPECT_LT(distance(r.cab.head_offset_m, s.cab.head_offset_m), 1e-7);
  EXPECT_NEAR(r.cab.look_yaw_rad, 0.3, 1e-7);
  ASSERT_EQ(r.indicator_count, s.indicator_count);
  for (int n = 0; n < s.indicator_count; ++n)
    EXPECT_EQ(r.indicators[static_cast<std::size_t>(n)], s.indicators[static_cast<std::size_t>(n)]);
  ASSERT_EQ(r.entity_count, s.entity_count);
  double worst_m = 0.0, worst_rotation = 0.0;
  for (int n = 0; n < s.entity_count; ++n) {
    const auto& a = s.entities[static_cast<std::size_t>(n)];
    const auto& b = r.entities[static_cast<std::size_t>(n)];
    EXPECT_EQ(a.index, b.index);
    EXPECT_EQ(a.flags, b.flags);
    worst_m = std::max(worst_m, distance(a.pose.position, b.pose.position));
    worst_rotation = std::max(worst_rotation, rotation_difference(a.pose.rotation, b.pose.rotation));
  }
  EXPECT_LT(worst_m, 1e-4);  // floats: 4 um at 100 m
  EXPECT_LT(worst_rotation, 1e-6);
  ASSERT_EQ(r.rope_count, s.rope_count);
  for (int k = 0; k < s.rope_count; ++k) {
    ASSERT_EQ(r.rope_points[static_cast<std::size_t>(k)], s.rope_points[static_cast<std::size_t>(k)]);
    for (int p = 0; p < s.rope_points[static_cast<std::size_t>(k)]; ++p) {
      const std::size_t i = s.rope_first[static_cast<std::size_t>(k)] + static_cast<std::size_t>(p);
      const std::size_t j = r.rope_first[static_cast<std::size_t>(k)] + static_cast<std::size_t>(p);
      EXPECT_LT(distance(r.points[j], s.points[i]), 1e-4);
    }
  }
  // the material: every grid's heights exactly, its pose, the parcels in flight
  ASSERT_EQ(got.bulk.grids.size(), sent.bulk.grids.size());
  for (std::size_t g = 0; g < sent.bulk.grids.size(); ++g) {
    EXPECT_EQ(got.bulk.grids[g].heights, sent.bulk.grids[g].heights) << "grid " << g;
    EXPECT_EQ(got.bulk.grids[g].cell_m, static_cast<float>(sent.bulk.grids[g].cell_m));
    EXPECT_EQ(got.bulk.grids[g].tile_version, sent.bulk.grids[g].tile_version);
    EXPECT_LT(distance(got.bulk.grids[g].pose.position, sent.bulk.grids[g].pose.position), 1e-4);
  }
  EXPECT_EQ(got.bulk.parcels.size(), sent.bulk.parcels.size());
}

TEST(ChannelFrame, TheChannelsPictureIsTheStationsPicture) {
  for (const char* exercise : {"sts_discharge", "mhc_coal_discharge"}) {
    const Sent sent = run(exercise, 30.0);
    const Received got = send(sent);
    ig::Looks looks = ig::load_shipped_looks(HARBOUR_DATA_DIR, sim::machine_kinds());
    ig::ImageGenerator station(sent.scene, looks.visuals, kWidth, kHeight);
    ig::ImageGenerator channel(scene_from(scene_message(sent.scene, 1)), looks.visuals, kWidth, kHeight);
    for (ig::ImageGenerator* generator : {&station, &channel}) {
      generator->use(looks);
      generator->set_view(ig::view_named("cab"));
    }
    station.update(*sent.snapshot);
    if (!sent.bulk.grids.empty()) station.update_bulk(sent.bulk);
    channel.update(*got.snapshot);
    if (!got.bulk.grids.empty()) channel.update_bulk(got.bulk);
    station.render();
    channel.render();
    // float positions move an edge by a pixel here and there; nothing else may differ
    const double differing = share_differing(station.render_result(), channel.render_result(), 8);
    EXPECT_LT(differing, 0.002) << exercise;
    // and the comparison sees a change: the same moment with the grab or spreader a metre away
    scene::Snapshot moved = *got.snapshot;
    for (int n = 0; n < moved.entity_count; ++n)
      moved.entities[static_cast<std::size_t>(n)].pose.position.z += 1.0;
    channel.update(moved);
    channel.render();
    EXPECT_GT(share_differing(station.render_result(), channel.render_result(), 8), 0.01) << exercise;
  }
}

TEST(ChannelFrame, TilesGoWhenTheyChangeAndABadTileIsRefused) {
  const Sent sent = run("mhc_coal_discharge", 1.0);
  ASSERT_FALSE(sent.bulk.grids.empty());
  std::vector<std::vector<std::uint32_t>> versions;
  int first = 0, again = 0, after_change = 0;
  scene::BulkView got;
  changed_bulk_tiles(sent.bulk, 1, versions, [&](const ChannelBulkTile& tile) {
    apply_bulk_tile(tile, got);
    ++first;
  });
  int tiles = 0;
  for (const auto& grid : sent.bulk.grids)
    tiles += grid.tiles_x * grid.tiles_y;
  EXPECT_EQ(first, tiles);
  changed_bulk_tiles(sent.bulk, 1, versions, [&](const ChannelBulkTile&) { ++again; });
  EXPECT_EQ(again, 0);
  scene::BulkView changed = sent.bulk;
  ++changed.grids[0].tile_version[1];
  changed.grids[0].heights[static_cast<std::size_t>(changed.grids[0].tile_cells)] += 0.5f;  // in tile 1
  ChannelBulkTile sent_tile;
  changed_bulk_tiles(changed, 1, versions, [&](const ChannelBulkTile& tile) {
    sent_tile = tile;
    ++after_change;
  });
  EXPECT_EQ(after_change, 1);
  EXPECT_EQ(sent_tile.tile(), 1);
  ASSERT_TRUE(apply_bulk_tile(sent_tile, got));
  EXPECT_EQ(got.grids[0].heights, changed.grids[0].heights);
  // a tile whose heights do not fit its own shape (a foreign writer's) changes nothing
  const std::vector<float> before = got.grids[0].heights;
  ChannelBulkTile bad = sent_tile;
  bad.heights_m().pop_back();
  EXPECT_FALSE(apply_bulk_tile(bad, got));
  bad = sent_tile;
  bad.tile(60000);
  EXPECT_FALSE(apply_bulk_tile(bad, got));
  EXPECT_EQ(got.grids[0].heights, before);
}

}  // namespace
}  // namespace harbour::net
