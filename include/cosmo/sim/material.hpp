#pragma once
// Surface materials of the synthetic world: how bright they are to a 865 nm LiDAR and how they scatter.
#include <array>
#include <cstdint>

namespace cosmo::sim {

enum Material : std::uint8_t {
  kGrass = 0,
  kAsphalt,
  kPaving,    ///< footpaths, plazas
  kConcrete,  ///< building facades, kerbs
  kBrick,
  kGlassFacade,
  kWall,
  kFence,
  kBark,     ///< tree trunks
  kFoliage,  ///< tree canopies (porous: extra depth spread and partial returns)
  kMetal,    ///< poles
  kCarPaint,
  kCount
};

struct MaterialProps {
  float reflectivity;  ///< Lambertian reflectivity, 0..1
  float depth_spread;  ///< extra uniform range spread behind the surface (m): penetration into foliage
  float return_prob;   ///< probability that a return is produced at all (before range/incidence losses)
};

/// Table indexed by Material.
inline const std::array<MaterialProps, kCount>& materialTable() {
  static const std::array<MaterialProps, kCount> table{{
      {0.30f, 0.00f, 0.99f},   // grass
      {0.08f, 0.00f, 0.99f},   // asphalt (dark)
      {0.25f, 0.00f, 0.99f},   // paving
      {0.35f, 0.00f, 0.995f},  // concrete
      {0.28f, 0.00f, 0.995f},  // brick
      {0.10f, 0.00f, 0.80f},   // glass facade (specular: many lost returns)
      {0.30f, 0.00f, 0.995f},  // wall
      {0.20f, 0.00f, 0.60f},   // fence (mesh: partial returns)
      {0.25f, 0.00f, 0.99f},   // bark
      {0.35f, 0.40f, 0.85f},   // foliage
      {0.45f, 0.00f, 0.99f},   // metal pole
      {0.40f, 0.00f, 0.97f},   // car paint
  }};
  return table;
}

}  // namespace cosmo::sim
