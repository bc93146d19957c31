#pragma once

#include "harbour/bulk/BulkWorld.h"
#include "harbour/scene/BulkView.h"

namespace harbour::bulk {

/// Publishes a bulk world into `view`: sizes it on first use, then copies only the tiles whose version moved
/// on since the last publish, and the parcels. Returns the number of tiles copied.
int publish(const BulkWorld& world, scene::BulkView& view);

}  // namespace harbour::bulk
