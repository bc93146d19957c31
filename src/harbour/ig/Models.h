#pragma once

#include <osg/Geometry>
#include <osg/ref_ptr>

#include "harbour/core/Vec3.h"

namespace harbour::ig {

/// Flat-shaded triangles with a normal and a colour at every vertex, built face by face: the procedural
/// models' geometry (one draw per model, whatever its colours).
class MeshBuilder {
 public:
  MeshBuilder();
  /// A planar quad a-b-c-d (in order round it), turned so its normal points along `outward`.
  void quad(const osg::Vec3& a, const osg::Vec3& b, const osg::Vec3& c, const osg::Vec3& d,
            const osg::Vec3& outward, const osg::Vec4& colour);
  /// A triangle, turned so its normal points along `outward`.
  void triangle(const osg::Vec3& a, const osg::Vec3& b, const osg::Vec3& c, const osg::Vec3& outward,
                const osg::Vec4& colour);
  /// An axis-aligned box round `centre` with half sides `half`.
  void box(const osg::Vec3& centre, const osg::Vec3& half, const osg::Vec4& colour);
  /// Another geometry's triangles (drawn as GL_TRIANGLES with normals and colours per vertex), moved by
  /// `offset`.
  void append(const osg::Geometry& geometry, const osg::Vec3& offset);
  std::size_t triangle_count() const { return vertices_->size() / 3; }
  bool empty() const { return vertices_->empty(); }
  osg::ref_ptr<osg::Geometry> build() const;

 private:
  osg::ref_ptr<osg::Vec3Array> vertices_, normals_;
  osg::ref_ptr<osg::Vec4Array> colours_;
};

/// An ISO series 1 dry freight container filling a box of `size_m` round the origin (x along its length,
/// y across, z up): corner castings (ISO 1161: 178 x 162 x 118 mm) with their apertures, corner posts, top
/// and bottom rails, side walls, front wall and roof of trapezoidal corrugated steel (a dry van's usual
/// profile: 36 mm deep on a 278 mm pitch, the roof's 20 mm), and at its -x end two door leaves with four
/// locking bars, their cams and handles, and hinges. Painted `paint`; the door hardware galvanised grey.
osg::ref_ptr<osg::Geometry> iso_container(const core::Vec3& size_m, const osg::Vec4& paint);

/// A tyre on its rim filling a box of `size_m` round the origin: the axle along the side that differs
/// from the other two (equal: the diameter). A lugged tread staggered from shoulder to shoulder, rounded
/// shoulders, sidewalls (rubber: ig/Materials.h), a dished rim with its hub and wheel nuts. `segments` round
/// it (the lugs only from 24 on: a far level of detail draws a smooth tyre).
osg::ref_ptr<osg::Geometry> tyre(const core::Vec3& size_m, const osg::Vec4& rubber_colour,
                                 const osg::Vec4& rim, int segments);

/// A clamshell grab's shell hanging from its pivot at the origin, shut: a bucket `size_m.y` wide whose back
/// curves (a quarter ellipse) from its lip `hinge_m` below the pivot, under the pivot, out to `size_m.x` on
/// +x and up `size_m.z`; its two side plates; a hardened cutting edge along the lip; two arms from the back's
/// top corners up to the pivot. Painted `paint` outside, worn steel inside (both faces drawn: an open grab
/// shows its inside).
osg::ref_ptr<osg::Geometry> clamshell(const core::Vec3& size_m, double hinge_m, const osg::Vec4& paint);

/// A ship's hull filling a box of `size_m` round the origin (x across: the beam, y along: the length, the bow
/// at +y, z up from the keel at -size_m.z / 2): vertical sides turning into a flat bottom through a bilge of
/// a tenth of the beam's radius, parallel amidships; towards the bow the waterlines close in to a raked stem
/// (finer at the keel than at the deck), towards the stern to a transom 0.6 of the beam wide at the deck.
/// Painted `topsides` above `waterline_m` (from the keel) and `bottom` under it; a flat deck of `deck` (alpha
/// 0: none) left open from `open_from_m` to `open_to_m` along y (the holds, open to the sky inside it).
osg::ref_ptr<osg::Geometry> hull(const core::Vec3& size_m, const osg::Vec4& topsides, const osg::Vec4& bottom,
                                 double waterline_m, const osg::Vec4& deck, double open_from_m = 0.0,
                                 double open_to_m = 0.0);

/// The axle's axis (0 x, 1 y, 2 z) of a tyre filling `size_m`, or -1 where no two sides are equal.
int tyre_axis(const core::Vec3& size_m);

/// A solid of revolution filling a box of `size_m` round the origin (a tyre, a cylinder): its axis along the
/// side that differs (tyre_axis; x where none does), its radius and half length.
struct Revolved {
  explicit Revolved(const core::Vec3& size_m);
  /// the point at angle `theta` round the axis, `r` from it and `w` along it
  osg::Vec3 at(float theta, float r, float w) const;
  int axis;
  float radius, half_length;
};

}  // namespace harbour::ig
