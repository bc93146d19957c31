#pragma once

#include <cstddef>
#include <cstdint>

#include "harbour/net/DdsLink.h"
#include "harbour/scene/BulkView.h"
#include "harbour/scene/Snapshot.h"

namespace harbour::net {

/// The network's form of a scene and of a published state (entities in scene order, poses as x, y, z and
/// a quaternion x, y, z, w; an entity missing from the snapshot keeps a zero pose): what the stations
/// publish and the console's replays send alike.
StationScene scene_message(const scene::SceneDescription& scene, std::int64_t attempt);
StationState state_message(const scene::Snapshot& snapshot, std::size_t entity_count, std::int64_t attempt);
/// The bulk material's surfaces as the console's 3D view draws them: at most kMostBulkGrids grids, each
/// coarsened to blocks of cells (the block's highest cell) so that all fit in kMostBulkSamples samples, at
/// most 64 on a side.
inline constexpr std::size_t kMostBulkGrids = 8, kMostBulkSamples = 16384;
inline constexpr int kMostBulkSamplesPerSide = 64;
StationBulk bulk_message(const scene::BulkView& view, std::int64_t attempt, double time_s);

}  // namespace harbour::net
