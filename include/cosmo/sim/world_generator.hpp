#pragma once
// Procedural campus: a grid of blocks separated by streets (some turned into footpaths, some blocks crossed
// by diagonal footpaths), each block filled with buildings (boxes, L-shapes, courtyards), a row of identical
// buildings (repeated in several blocks: look-alike places), a park (trees, paths), a car park or an open plaza;
// block sides optionally lined with terraces of one repeated house (look-alike streets); streets
// lined with kerbs, poles, tree rows, walls/fences and parked cars; gentle terrain under everything.
// What changes between the days the trials are recorded (parked cars moved or gone, people on the pavements,
// tree canopies grown or blown) is kept apart (WorldLayout) and drawn anew for every trial (trialWorld): a
// place seen by two trials is the same place with different clutter, as on a real campus.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cosmo/common/config.hpp"
#include "cosmo/sim/world.hpp"

namespace cosmo::sim {

struct WorldParams {
  int blocks_x = 4;         ///< blocks along x (junctions: blocks_x + 1)
  int blocks_y = 3;         ///< blocks along y
  double block_min = 70.0;  ///< block pitch range (street centre to street centre), m
  double block_max = 100.0;
  double street_half_width = 4.0;     ///< kerb offset from the street centre line, m
  double sidewalk_width = 3.0;        ///< paved strip outside the kerb, m
  double footpath_half_width = 1.5;   ///< m
  double footpath_fraction = 0.15;    ///< interior streets turned into footpaths (no kerbs, no cars)
  double diagonal_fraction = 0.35;    ///< park blocks crossed by a diagonal footpath
  double building_height_min = 6.0;   ///< m
  double building_height_max = 24.0;  ///< m
  double p_buildings = 0.45;          ///< block type weights: varied buildings,
  double p_row = 0.2;                 ///< rows of identical buildings (one shared template),
  double p_park = 0.2;                ///< park with trees,
  double p_parking = 0.15;            ///< car park with rows of cars and lamp posts
  double tree_row_fraction = 0.5;     ///< street sides lined with a row of identical trees
  double tree_spacing = 9.0;          ///< m
  double pole_spacing = 28.0;         ///< lamp posts along streets, m (0: none)
  double parked_car_fraction = 0.3;   ///< street sides with parked cars
  double wall_fraction = 0.25;        ///< block sides with a wall or fence
  double outer_ring = 40.0;           ///< depth of the built-up / wooded ring outside the outer streets, m
  double terrain_margin = 90.0;       ///< terrain beyond the outer ring, m
  double car_change = 0.0;            ///< per trial: share of parked cars moved along the kerb (1-5 m) or gone
  double people_per_100m = 0.0;       ///< per trial: pedestrians per 100 m of path network, on the pavements
  double foliage_change = 0.0;        ///< per trial: relative change of every tree canopy (size and centre)
  /// Block sides along streets lined with a terrace of identical houses (one house for the whole world, the
  /// terraces centred on their side): with equal blocks, places a block apart along a long street look alike to
  /// ScanContext and align convincingly, as repeated façades do on real campuses. 0: none.
  double terrace_fraction = 0.0;
  double p_open = 0.0;  ///< block type weight: open plaza / lawn with little structure (benches)
  /// Street sides lined with a hedge (1 m thick, 1.4 m high, behind the pavement): foliage, which a LiDAR with
  /// LidarModel::foliage_mean_free_path sees as a volume that returns at a random depth. 0: none.
  double hedge_fraction = 0.0;
  TerrainParams terrain;

  static WorldParams fromConfig(const ConfigNode& node);
  /// Every parameter as text (for the cache key).
  std::string describe() const;
};

/// A parked car: where it was generated.
struct ParkedCar {
  double x = 0, y = 0, yaw = 0, length = 4.4, width = 1.8, body_top = 1.0, cabin_top = 1.5;
};

/// The world before the trials' clutter: fixed objects, and the objects that change from trial to trial.
struct WorldLayout {
  WorldParams params;
  Terrain terrain;
  std::vector<Primitive> fixed;     ///< buildings, walls, kerbs, poles, tree trunks, ...
  std::vector<ParkedCar> cars;      ///< parked cars as generated
  std::vector<Primitive> canopies;  ///< tree canopies as generated
  PathNetwork network;
};

WorldLayout generateLayout(const WorldParams& params, std::uint64_t seed);
/// The world as generated (every car, no people, canopies unchanged) when `trial_seed` is empty; otherwise
/// the world of one trial: cars moved or gone (car_change), people placed (people_per_100m), canopies
/// changed (foliage_change), all drawn from `trial_seed`.
World layoutWorld(const WorldLayout& layout, std::optional<std::uint64_t> trial_seed = std::nullopt);
/// The world and its path network for `seed` (= layoutWorld(generateLayout(params, seed))).
World generateWorld(const WorldParams& params, std::uint64_t seed);
/// True when the parameters make trials differ (any of the per-trial changes is on).
bool changesPerTrial(const WorldParams& params);

}  // namespace cosmo::sim
