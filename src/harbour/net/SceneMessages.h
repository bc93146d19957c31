#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

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
/// The scene a StationScene describes (what a remote channel draws).
scene::SceneDescription scene_from(const StationScene& message);

/// Parcels of material in flight a frame carries (ChannelFrame::bulk_parcels' bound).
inline constexpr std::size_t kMostChannelParcels = 1024;
/// A remote channel's frame of a snapshot: everything the image generator reads of it, the bulk grids' poses
/// and the material in flight (of `bulk`, where there is one); positions as floats (30 um at 500 m).
ChannelFrame channel_frame(const scene::Snapshot& snapshot, const scene::BulkView* bulk,
                           std::int64_t attempt);
/// The snapshot a frame gives back (what the image generator reads of it; the rest as a new Snapshot has
/// it), and the grids' poses and the parcels into `bulk`'s grids (those it has) and parcels. Fields out of
/// their bounds (a foreign writer's) are cut to them.
void read_channel_frame(const ChannelFrame& frame, scene::Snapshot& snapshot, scene::BulkView* bulk);
/// The tiles of `view` whose version differs from `sent` (per grid, per tile; sized here), each to `send`;
/// `sent` then holds the versions sent.
void changed_bulk_tiles(const scene::BulkView& view, std::int64_t attempt,
                        std::vector<std::vector<std::uint32_t>>& sent,
                        const std::function<void(const ChannelBulkTile&)>& send);
/// Puts a tile's heights into `view` (its grid made or re-shaped to the tile's shape); false, nothing
/// written, where the tile does not fit its own shape (a foreign writer's).
bool apply_bulk_tile(const ChannelBulkTile& tile, scene::BulkView& view);

}  // namespace harbour::net
