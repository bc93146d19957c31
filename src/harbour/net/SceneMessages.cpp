#include "harbour/net/SceneMessages.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>

namespace harbour::net {

StationScene scene_message(const scene::SceneDescription& description, std::int64_t attempt) {
  StationScene scene;
  scene.attempt(attempt);
  scene.machine(description.machine);
  const std::size_t count = std::min<std::size_t>(description.entities.size(), scene::kMaxEntities);
  std::vector<eprosima::fastrtps::fixed_string<48>> names, visuals;
  std::vector<float> extents;
  for (std::size_t n = 0; n < count; ++n) {
    names.emplace_back(description.entities[n].name.substr(0, 48));
    visuals.emplace_back(description.entities[n].visual.substr(0, 48));
    const core::Vec3& e = description.entities[n].half_extents_m;
    extents.insert(extents.end(),
                   {static_cast<float>(e.x), static_cast<float>(e.y), static_cast<float>(e.z)});
  }
  scene.entity_names(names);
  scene.entity_visuals(visuals);
  scene.entity_half_extents_m(extents);
  std::vector<eprosima::fastrtps::fixed_string<48>> indicators;
  for (std::size_t n = 0; n < description.indicators.size() && n < scene::kMaxIndicators; ++n)
    indicators.emplace_back(description.indicators[n].substr(0, 48));
  scene.indicator_names(indicators);
  scene.machine_entities(description.machine_entities);
  scene.rope_count(description.rope_count);
  return scene;
}

scene::SceneDescription scene_from(const StationScene& message) {
  scene::SceneDescription description;
  description.machine = message.machine().to_string();
  const std::vector<float>& extents = message.entity_half_extents_m();
  for (std::size_t n = 0; n < message.entity_names().size(); ++n) {
    scene::SceneDescription::Entity e;
    e.name = message.entity_names()[n].to_string();
    e.visual = n < message.entity_visuals().size() ? message.entity_visuals()[n].to_string() : "";
    if (3 * n + 2 < extents.size())
      e.half_extents_m = {extents[3 * n], extents[3 * n + 1], extents[3 * n + 2]};
    description.entities.push_back(std::move(e));
  }
  for (const auto& name : message.indicator_names())
    description.indicators.push_back(name.to_string());
  description.machine_entities =
      std::clamp<int>(message.machine_entities(), 0, static_cast<int>(description.entities.size()));
  description.rope_count = std::clamp<int>(message.rope_count(), 0, scene::kMaxRopes);
  return description;
}

StationBulk bulk_message(const scene::BulkView& view, std::int64_t attempt, double time_s) {
  StationBulk bulk;
  bulk.attempt(attempt);
  bulk.time_s(time_s);
  const std::size_t grids = std::min<std::size_t>(view.grids.size(), kMostBulkGrids);
  // every grid the same budget of samples, at most 64 x 64
  const int budget = std::min(kMostBulkSamplesPerSide * kMostBulkSamplesPerSide,
                              static_cast<int>(kMostBulkSamples / std::max<std::size_t>(grids, 1)));
  for (std::size_t g = 0; g < grids; ++g) {
    const scene::BulkView::Grid& grid = view.grids[g];
    int block = 1;  // cells per sample side
    while ((grid.cells_x + block - 1) / block * ((grid.cells_y + block - 1) / block) > budget)
      ++block;
    const int nx = (grid.cells_x + block - 1) / block, ny = (grid.cells_y + block - 1) / block;
    bulk.samples_x().push_back(static_cast<std::uint16_t>(nx));
    bulk.samples_y().push_back(static_cast<std::uint16_t>(ny));
    bulk.sample_m().push_back(static_cast<float>(grid.cell_m * block));
    const core::Quat q = core::Quat::from(grid.pose.rotation);
    for (const double v :
         {grid.pose.position.x, grid.pose.position.y, grid.pose.position.z, q.x, q.y, q.z, q.w})
      bulk.grid_poses().push_back(static_cast<float>(v));
    for (int sj = 0; sj < ny; ++sj)
      for (int si = 0; si < nx; ++si) {
        float top = 0.0f;  // the block's highest cell: a pile's crest stays
        for (int j = sj * block; j < std::min((sj + 1) * block, grid.cells_y); ++j)
          for (int i = si * block; i < std::min((si + 1) * block, grid.cells_x); ++i)
            top = std::max(top, grid.heights[static_cast<std::size_t>(j * grid.cells_x + i)]);
        bulk.heights_m().push_back(top);
      }
  }
  return bulk;
}

StationState state_message(const scene::Snapshot& snapshot, std::size_t entity_count, std::int64_t attempt) {
  StationState state;
  state.attempt(attempt);
  state.step(snapshot.step);
  state.time_s(snapshot.time_s);
  state.held(snapshot.held);
  state.wind_mps({static_cast<float>(snapshot.wind_mps.x), static_cast<float>(snapshot.wind_mps.y),
                  static_cast<float>(snapshot.wind_mps.z)});
  state.time_of_day_h(snapshot.time_of_day_h);
  state.visibility_m(snapshot.visibility_m);
  state.rain_mm_per_h(snapshot.rain_mm_per_h);
  state.cloud_oktas(snapshot.cloud_oktas);
  state.water_level_m(snapshot.sea.water_level_m);
  state.indicators().assign(snapshot.indicators.begin(),
                            snapshot.indicators.begin() + snapshot.indicator_count);
  // every entity in scene order (one not in this snapshot, or hidden in it, keeps a zero pose: not drawn)
  std::vector<float>& poses = state.entity_poses();
  poses.assign(std::min<std::size_t>(entity_count, scene::kMaxEntities) * 7, 0.0f);
  for (int n = 0; n < snapshot.entity_count; ++n) {
    const scene::Snapshot::Entity& e = snapshot.entities[static_cast<std::size_t>(n)];
    if (e.index * 7 + 7 > poses.size() || (e.flags & scene::Snapshot::kHidden) != 0) continue;
    const core::Quat q = core::Quat::from(e.pose.rotation);
    float* p = &poses[e.index * 7];
    for (const double v : {e.pose.position.x, e.pose.position.y, e.pose.position.z, q.x, q.y, q.z, q.w})
      *p++ = static_cast<float>(v);
  }
  for (int r = 0; r < snapshot.rope_count; ++r) {
    const std::size_t first = snapshot.rope_first[static_cast<std::size_t>(r)];
    const std::size_t count = snapshot.rope_points[static_cast<std::size_t>(r)];
    state.rope_point_counts().push_back(static_cast<std::uint16_t>(count));
    for (std::size_t k = first; k < first + count && k < snapshot.points.size(); ++k)
      state.rope_points_m().insert(state.rope_points_m().end(), {static_cast<float>(snapshot.points[k].x),
                                                                 static_cast<float>(snapshot.points[k].y),
                                                                 static_cast<float>(snapshot.points[k].z)});
  }
  return state;
}

namespace {

enum ChannelFlags : std::uint8_t {
  kFrameHeld = 1,
  kFrameDiverged = 2,
  kFramePowerOff = 4,
  kFrameAwaitingZero = 8,
  kFrameEmergencyStop = 16
};

template <std::size_t N>
std::array<float, N> floats(std::initializer_list<double> values) {
  std::array<float, N> out{};
  std::size_t n = 0;
  for (const double v : values)
    out[n++] = static_cast<float>(v);
  return out;
}

void append_pose(std::vector<float>& out, const core::Pose& pose) {
  const core::Quat q = core::Quat::from(pose.rotation);
  for (const double v : {pose.position.x, pose.position.y, pose.position.z, q.x, q.y, q.z, q.w})
    out.push_back(static_cast<float>(v));
}

template <class T>
core::Pose pose_from(const T* p) {
  core::Pose pose;
  pose.position = {p[0], p[1], p[2]};
  pose.rotation = core::Quat{p[3], p[4], p[5], p[6]}.matrix();
  return pose;
}

}  // namespace

ChannelFrame channel_frame(const scene::Snapshot& s, const scene::BulkView* bulk, std::int64_t attempt) {
  ChannelFrame f;
  f.attempt(attempt);
  f.step(s.step);
  f.time_s(s.time_s);
  f.flags(static_cast<std::uint8_t>(
      (s.held ? kFrameHeld : 0) | (s.diverged ? kFrameDiverged : 0) | (s.power_off ? kFramePowerOff : 0) |
      (s.awaiting_zero ? kFrameAwaitingZero : 0) | (s.emergency_stop ? kFrameEmergencyStop : 0)));
  f.devices_missing(s.devices_missing);
  f.hand_signal(s.hand_signal);
  f.hand_signal_at_s(s.hand_signal_at_s);
  f.wind_mps(floats<3>({s.wind_mps.x, s.wind_mps.y, s.wind_mps.z}));
  f.time_of_day_h(s.time_of_day_h);
  f.visibility_m(s.visibility_m);
  f.rain_mm_per_h(s.rain_mm_per_h);
  f.cloud_oktas(s.cloud_oktas);
  f.day_of_year(s.day_of_year);
  f.latitude_deg(s.latitude_deg);
  f.water_level_m(s.sea.water_level_m);
  f.sea_reference_m(floats<3>({s.sea.reference_m.x, s.sea.reference_m.y, s.sea.reference_m.z}));
  for (int n = 0; n < std::clamp(s.sea.swell_count, 0, scene::kMaxSwells); ++n) {
    const scene::Snapshot::Swell& w = s.sea.swells[static_cast<std::size_t>(n)];
    for (const double v : {w.amplitude_m, w.period_s, w.phase_rad, w.direction_rad})
      f.swells().push_back(static_cast<float>(v));
  }
  const core::Quat q = core::Quat::from(s.cab.pose.rotation);
  f.cab_pose({s.cab.pose.position.x, s.cab.pose.position.y, s.cab.pose.position.z, q.x, q.y, q.z, q.w});
  f.cab_eye_m(floats<3>({s.cab.eye_m.x, s.cab.eye_m.y, s.cab.eye_m.z}));
  const scene::CabSight& sight = s.cab.sight;
  f.cab_sight(floats<5>(
      {sight.yaw_rad, sight.pitch_rad, sight.fov_vertical_rad, sight.look_yaw_rad, sight.look_pitch_rad}));
  f.head_offset_m(floats<3>({s.cab.head_offset_m.x, s.cab.head_offset_m.y, s.cab.head_offset_m.z}));
  f.head_yaw_pitch_roll_rad(floats<3>(
      {s.cab.head_yaw_pitch_roll_rad.x, s.cab.head_yaw_pitch_roll_rad.y, s.cab.head_yaw_pitch_roll_rad.z}));
  f.look_yaw_pitch_rad(floats<2>({s.cab.look_yaw_rad, s.cab.look_pitch_rad}));
  f.indicators().assign(s.indicators.begin(),
                        s.indicators.begin() + std::clamp(s.indicator_count, 0, scene::kMaxIndicators));
  const int entities = std::clamp(s.entity_count, 0, scene::kMaxEntities);
  f.entity_index().reserve(static_cast<std::size_t>(entities));
  f.entity_flags().reserve(static_cast<std::size_t>(entities));
  f.entity_poses().reserve(static_cast<std::size_t>(entities) * 7);
  for (int n = 0; n < entities; ++n) {
    const scene::Snapshot::Entity& e = s.entities[static_cast<std::size_t>(n)];
    f.entity_index().push_back(static_cast<std::uint16_t>(e.index));
    f.entity_flags().push_back(static_cast<std::uint8_t>(e.flags));
    append_pose(f.entity_poses(), e.pose);
  }
  for (int r = 0; r < std::clamp(s.rope_count, 0, scene::kMaxRopes); ++r) {
    const std::size_t first = s.rope_first[static_cast<std::size_t>(r)];
    const std::size_t count = s.rope_points[static_cast<std::size_t>(r)];
    f.rope_point_counts().push_back(static_cast<std::uint16_t>(count));
    for (std::size_t k = first; k < first + count && k < s.points.size(); ++k)
      for (const double v : {s.points[k].x, s.points[k].y, s.points[k].z})
        f.rope_points_m().push_back(static_cast<float>(v));
  }
  if (bulk) {
    for (std::size_t g = 0; g < bulk->grids.size() && g < kMostBulkGrids; ++g)
      append_pose(f.bulk_grid_poses(), bulk->grids[g].pose);
    for (std::size_t p = 0; p < bulk->parcels.size() && p < kMostChannelParcels; ++p) {
      const scene::BulkView::Parcel& parcel = bulk->parcels[p];
      for (const double v : {parcel.position_m.x, parcel.position_m.y, parcel.position_m.z, parcel.volume_m3})
        f.bulk_parcels().push_back(static_cast<float>(v));
    }
  }
  return f;
}

void read_channel_frame(const ChannelFrame& f, scene::Snapshot& s, scene::BulkView* bulk) {
  s.step = f.step();
  s.time_s = f.time_s();
  s.held = (f.flags() & kFrameHeld) != 0;
  s.diverged = (f.flags() & kFrameDiverged) != 0;
  s.power_off = (f.flags() & kFramePowerOff) != 0;
  s.awaiting_zero = (f.flags() & kFrameAwaitingZero) != 0;
  s.emergency_stop = (f.flags() & kFrameEmergencyStop) != 0;
  s.devices_missing = f.devices_missing();
  s.hand_signal = f.hand_signal();
  s.hand_signal_at_s = f.hand_signal_at_s();
  s.wind_mps = {f.wind_mps()[0], f.wind_mps()[1], f.wind_mps()[2]};
  s.time_of_day_h = f.time_of_day_h();
  s.visibility_m = f.visibility_m();
  s.rain_mm_per_h = f.rain_mm_per_h();
  s.cloud_oktas = f.cloud_oktas();
  s.day_of_year = f.day_of_year();
  s.latitude_deg = f.latitude_deg();
  s.sea.water_level_m = f.water_level_m();
  s.sea.reference_m = {f.sea_reference_m()[0], f.sea_reference_m()[1], f.sea_reference_m()[2]};
  s.sea.swell_count = static_cast<int>(std::min<std::size_t>(f.swells().size() / 4, scene::kMaxSwells));
  for (int n = 0; n < s.sea.swell_count; ++n) {
    const float* w = &f.swells()[static_cast<std::size_t>(n) * 4];
    s.sea.swells[static_cast<std::size_t>(n)] = {w[0], w[1], w[2], w[3]};
  }
  s.cab.pose = pose_from(f.cab_pose().data());
  s.cab.eye_m = {f.cab_eye_m()[0], f.cab_eye_m()[1], f.cab_eye_m()[2]};
  const auto& sight = f.cab_sight();
  s.cab.sight = {sight[0], sight[1], sight[2], sight[3], sight[4]};
  s.cab.head_offset_m = {f.head_offset_m()[0], f.head_offset_m()[1], f.head_offset_m()[2]};
  const auto& head = f.head_yaw_pitch_roll_rad();
  s.cab.head_yaw_pitch_roll_rad = {head[0], head[1], head[2]};
  s.cab.look_yaw_rad = f.look_yaw_pitch_rad()[0];
  s.cab.look_pitch_rad = f.look_yaw_pitch_rad()[1];
  s.indicator_count = static_cast<int>(std::min<std::size_t>(f.indicators().size(), scene::kMaxIndicators));
  std::copy_n(f.indicators().begin(), s.indicator_count, s.indicators.begin());
  const std::size_t entities = std::min({f.entity_index().size(), f.entity_flags().size(),
                                         f.entity_poses().size() / 7, std::size_t{scene::kMaxEntities}});
  s.entity_count = static_cast<int>(entities);
  for (std::size_t n = 0; n < entities; ++n)
    s.entities[n] = {f.entity_index()[n], f.entity_flags()[n], pose_from(&f.entity_poses()[n * 7])};
  s.rope_count = 0;
  std::size_t point = 0;
  for (std::size_t r = 0; r < f.rope_point_counts().size() && r < scene::kMaxRopes; ++r) {
    const std::size_t count = f.rope_point_counts()[r];
    if ((point + count) * 3 > f.rope_points_m().size() || point + count > scene::kMaxRopePoints) break;
    s.rope_first[r] = static_cast<std::uint16_t>(point);
    s.rope_points[r] = static_cast<std::uint16_t>(count);
    for (std::size_t k = point; k < point + count; ++k)
      s.points[k] = {f.rope_points_m()[3 * k], f.rope_points_m()[3 * k + 1], f.rope_points_m()[3 * k + 2]};
    point += count;
    s.rope_count = static_cast<int>(r) + 1;
  }
  if (!bulk) return;
  for (std::size_t g = 0; g < bulk->grids.size() && 7 * g + 7 <= f.bulk_grid_poses().size(); ++g)
    bulk->grids[g].pose = pose_from(&f.bulk_grid_poses()[7 * g]);
  bulk->parcels.resize(f.bulk_parcels().size() / 4);
  for (std::size_t p = 0; p < bulk->parcels.size(); ++p) {
    const float* v = &f.bulk_parcels()[4 * p];
    bulk->parcels[p] = {{v[0], v[1], v[2]}, v[3]};
  }
}

void changed_bulk_tiles(const scene::BulkView& view, std::int64_t attempt,
                        std::vector<std::vector<std::uint32_t>>& sent,
                        const std::function<void(const ChannelBulkTile&)>& send) {
  const std::size_t grids = std::min<std::size_t>(view.grids.size(), kMostBulkGrids);
  sent.resize(grids);
  for (std::size_t g = 0; g < grids; ++g) {
    const scene::BulkView::Grid& grid = view.grids[g];
    if (grid.tile_cells <= 0 || grid.tile_cells * grid.tile_cells > 4096) continue;
    sent[g].resize(grid.tile_version.size(), ~std::uint32_t{0});
    for (int ty = 0; ty < grid.tiles_y; ++ty)
      for (int tx = 0; tx < grid.tiles_x; ++tx) {
        const std::size_t t = static_cast<std::size_t>(ty * grid.tiles_x + tx);
        if (t >= grid.tile_version.size() || sent[g][t] == grid.tile_version[t]) continue;
        ChannelBulkTile tile;
        tile.attempt(attempt);
        tile.grid(static_cast<std::uint16_t>(g));
        tile.tile(static_cast<std::uint16_t>(t));
        tile.version(grid.tile_version[t]);
        tile.cells_x(static_cast<std::uint16_t>(grid.cells_x));
        tile.cells_y(static_cast<std::uint16_t>(grid.cells_y));
        tile.tile_cells(static_cast<std::uint16_t>(grid.tile_cells));
        tile.cell_m(static_cast<float>(grid.cell_m));
        for (int j = ty * grid.tile_cells; j < std::min((ty + 1) * grid.tile_cells, grid.cells_y); ++j)
          for (int i = tx * grid.tile_cells; i < std::min((tx + 1) * grid.tile_cells, grid.cells_x); ++i)
            tile.heights_m().push_back(grid.heights[static_cast<std::size_t>(j * grid.cells_x + i)]);
        send(tile);
        sent[g][t] = grid.tile_version[t];
      }
  }
}

bool apply_bulk_tile(const ChannelBulkTile& tile, scene::BulkView& view) {
  const int cells_x = tile.cells_x(), cells_y = tile.cells_y(), side = tile.tile_cells();
  if (tile.grid() >= kMostBulkGrids || side <= 0 || cells_x <= 0 || cells_y <= 0) return false;
  const int tiles_x = (cells_x + side - 1) / side, tiles_y = (cells_y + side - 1) / side;
  const int tx = tile.tile() % tiles_x, ty = tile.tile() / tiles_x;
  if (ty >= tiles_y) return false;
  const int i0 = tx * side, i1 = std::min(i0 + side, cells_x), j0 = ty * side,
            j1 = std::min(j0 + side, cells_y);
  if (tile.heights_m().size() != static_cast<std::size_t>((i1 - i0) * (j1 - j0))) return false;
  if (view.grids.size() <= tile.grid()) view.grids.resize(tile.grid() + 1u);
  scene::BulkView::Grid& grid = view.grids[tile.grid()];
  if (grid.cells_x != cells_x || grid.cells_y != cells_y || grid.tile_cells != side) {
    grid.cells_x = cells_x;
    grid.cells_y = cells_y;
    grid.tile_cells = side;
    grid.tiles_x = tiles_x;
    grid.tiles_y = tiles_y;
    // not yet had: differs from every version the station sends, so each is meshed as it comes
    grid.tile_version.assign(static_cast<std::size_t>(tiles_x * tiles_y), ~std::uint32_t{0});
    grid.heights.assign(static_cast<std::size_t>(cells_x * cells_y), 0.0f);
  }
  grid.cell_m = tile.cell_m();
  std::size_t k = 0;
  for (int j = j0; j < j1; ++j)
    for (int i = i0; i < i1; ++i)
      grid.heights[static_cast<std::size_t>(j * cells_x + i)] = tile.heights_m()[k++];
  grid.tile_version[tile.tile()] = tile.version();
  return true;
}

}  // namespace harbour::net
