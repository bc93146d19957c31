#pragma once

namespace harbour::scene {

/// Surface tags of the world's shapes: impacts report them, evaluation sorts collisions by them. Plain data
/// shared by every model (machines, vessel, trucks) and the evaluation, so none of them includes another.
enum Surface : int {
  kSurfaceGround = 0,
  kSurfaceQuay,
  kSurfaceContainer,
  kSurfaceSpreader,
  kSurfaceHull,
  kSurfaceCellGuide,
  kSurfaceHatchCover,
  kSurfaceTruck,
  kSurfaceFlipper,
  kSurfaceVehicle,  ///< a wheeled machine's chassis or trailer
};

}  // namespace harbour::scene
