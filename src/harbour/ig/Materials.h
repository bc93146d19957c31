#pragma once

#include <array>
#include <optional>
#include <string_view>

#include <osg/Vec4>

namespace harbour::ig {

/// What a surface is made of, for the lit shader's physically based shading (GGX microfacets): how rough it
/// is (perceptual roughness, squared to GGX's alpha) and whether it is a metal (a metal's colour is its
/// reflectance at normal incidence and it has no diffuse part; a dielectric reflects 4 % there).
enum class Surface : int { kPaint, kSteel, kGalvanised, kRubber, kConcrete, kGlass, kTimber, kBulk, kCount };

struct SurfaceFinish {
  std::string_view name;
  float roughness;
  float metalness;
  float texture;     ///< how strongly its colour, roughness and normal vary with the detail texture (0-1)
  float weathering;  ///< how strongly its upright faces streak (rust, water stains) (0-1)
};

/// Roughness and metalness: typical values of the physically based shading literature (Karis 2013; Lagarde
/// & de Rousiers 2014) for weathered industrial paint, worn bare steel, hot-dip galvanising, tyre rubber,
/// concrete, glass, sawn timber, a granular bulk surface (coal, grain). Texture and weathering: chosen by
/// eye (assumed).
inline constexpr std::array<SurfaceFinish, static_cast<std::size_t>(Surface::kCount)> kSurfaceFinishes{{
    {"paint", 0.50f, 0.0f, 0.15f, 0.5f},
    {"steel", 0.35f, 1.0f, 0.30f, 0.0f},
    {"galvanised", 0.50f, 1.0f, 0.35f, 0.3f},
    {"rubber", 0.85f, 0.0f, 0.15f, 0.0f},
    {"concrete", 0.92f, 0.0f, 0.22f, 0.5f},
    {"glass", 0.05f, 0.0f, 0.0f, 0.0f},
    {"timber", 0.80f, 0.0f, 0.40f, 0.3f},
    {"bulk", 0.95f, 0.0f, 0.50f, 0.0f},
}};
static_assert(kSurfaceFinishes.size() <= 8, "the lit shader's finishes[8]");

/// The surface called `name`, if there is one.
std::optional<Surface> surface_named(std::string_view name);
/// The names of every surface, for an error message: "paint, steel, ..."
std::string_view surface_names();

/// `colour` carrying `surface` to the lit shader in its alpha (1 - index/16: paint, the default, is an
/// alpha of 1; the lit scene is opaque, its alpha otherwise unused).
osg::Vec4 finished(const osg::Vec4& colour, Surface surface);

}  // namespace harbour::ig
