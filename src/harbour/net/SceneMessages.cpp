#include "harbour/net/SceneMessages.h"

#include <algorithm>
#include <cmath>

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
  return scene;
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

}  // namespace harbour::net
