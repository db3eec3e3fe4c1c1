#pragma once
/// @file config.hpp
/// The one configuration struct of an EgoOctree. Every field has a unit, a default and a typical
/// range; `validate()` is called once by the EgoOctree constructor and throws
/// `std::invalid_argument` naming the offending field and value.

#include <cstdint>

namespace eco {

/// How the root cell follows the sensor.
enum class Recentring {
  /// The root centre moves in whole steps of the quantum q = L / (2^k - 1); cells at depth >= k sit
  /// on a fixed world lattice, so re-centring only re-links the top k levels. Default.
  Quantised,
  /// The root is re-centred exactly on the sensor every frame (the paper's algorithm): subtrees
  /// whose bounds no longer fit their moved octant are rebuilt from their points.
  Exact,
};

/// Which scan points an update inserts.
enum class InsertPolicy {
  /// Only points in R_in = Box(p_t) \ Box(p_{t-1}) (the paper's policy; right for a static,
  /// pre-aggregated map streamed by pose).
  ShiftInOnly,
  /// Every scan point inside Box(p_t) (right for raw scans; pair it with a density cap or an age
  /// limit to bound memory while the sensor stands still).
  AllInBox,
};

/// Optional cap on points per world-aligned cell: at most `max_points` points are held in any cell
/// [i*cell_size, (i+1)*cell_size)^3 (walls in double: see EgoOctree::voxel_keys). A new point that
/// would exceed the cap is not inserted (the points already held are kept). Off while
/// `max_points == 0`. Counts are kept per cell as points come and go, so the test is O(1).
struct DensityCap {
  double cell_size = 0.0;    ///< [m] side of the density cell; typical 0.05–0.5; in (box_side / 262142, box_side].
  std::uint32_t max_points = 0;  ///< points per cell; 0 = cap off, typical 1–10, at most 1023.

  [[nodiscard]] bool enabled() const { return max_points > 0; }
};

/// The LiDAR as free-space clearing sees it: a spinning sensor at the origin of the sensor frame
/// (the frame of the scan and of the pose's rotation) whose returns are binned into a range image.
/// For a sensor-frame point v, in degrees:
///   azimuth   = atan2(v.y, v.x) * 180 / pi,   column = floor((azimuth + 180) / horizontal_resolution)
///                                                      mod columns, columns = ceil(360 / horizontal_resolution);
///   elevation = atan2(v.z, hypot(v.x, v.y)) * 180 / pi,
///                                            row = floor((elevation - vertical_fov_min) / vertical_resolution),
///   a point with elevation outside [vertical_fov_min, vertical_fov_max) or range |v| above
///   max_range is outside the image. Defaults: Velodyne HDL-64E as on KITTI (64 beams from -24.9 to
///   +2 degrees, ~0.42 degrees apart; ~0.08 degrees between firings, binned at 0.2). For another
///   sensor take its vertical field of view, its beam spacing (field of view / beams; the largest
///   spacing if uneven) as vertical_resolution, and two to three times its firing step as
///   horizontal_resolution, so that every pixel on a surface holds a return.
struct SensorModel {
  double vertical_fov_min = -24.9;      ///< [deg] elevation of the lowest beam; in [-90, 90).
  double vertical_fov_max = 2.0;        ///< [deg] just above the highest beam; in (vertical_fov_min, 90].
  double vertical_resolution = 0.42;    ///< [deg] row height, about the beam spacing; > 0.
  double horizontal_resolution = 0.2;   ///< [deg] column width; in (0, 360].
  double max_range = 100.0;             ///< [m] returns and held points farther away are not used; > 0.

  [[nodiscard]] int rows() const;     ///< rows of the range image: ceil(fov span / vertical_resolution)
  [[nodiscard]] int columns() const;  ///< columns: ceil(360 / horizontal_resolution)
};

/// Free-space clearing: each update removes the held points that the new scan shows to be empty
/// space, so moving objects leave no trails. A held point is cleared when it lies in the sensor's
/// image (SensorModel), some return came back in each row of its pixel and the 8 around it
/// (columns wrap around, rows stop at the image's edge), and the nearest of those returns is
/// farther than the point by more than `margin`: rays above, through and below it passed it, and
/// none of its neighbours stopped before it. Points behind surfaces, outside the field of view,
/// beyond max_range, or where a row around them got no return (a gap between beams, the sky) are
/// kept. The test uses the update's pose and every finite return of the scan (in the box or not)
/// and runs after the box moved (stage 2), before the scan's points are inserted.
/// With `arrivals` (on by default; it acts while clearing is enabled), a point the previous update
/// brought in is judged a second time, by the same rule, against the scan before the one that
/// brought it (from that scan's pose), and cleared when that scan saw through where it lies: it
/// filled space seen empty a frame earlier — something moved in — so it is held until the next
/// update only, and a car coming toward the sensor, hiding where it was, leaves no trail. The
/// update judges each point as it comes in and notes those that leave at the next; it keeps one
/// more range image. Turn it off for the cheaper rule alone (~5 % less update time).
/// The sensor is Config::sensor.
struct FreeSpaceClearing {
  bool enabled = false;   ///< off by default: the paper's behaviour, every trail kept
  double margin = 0.3;    ///< [m] a return must lie this much beyond a point to clear it; >= 0.01.
  bool arrivals = true;   ///< also clear arrivals into space the scan before saw empty (above)
};

/// Which per-point attributes of the scans (ScanView::ids, intensities, times) the tree stores and
/// returns with every query; each costs 4 bytes per held point. Off by default. A kept attribute
/// must come with every non-empty scan.
/// Times are stored as float offsets from a time origin, a multiple of 64 s kept within 128 s of
/// the latest time taken in (the way coordinates are kept near a precision origin), so a point's
/// time comes back within 2^-24 of its distance from that origin (8 us while it is recent).
struct KeptAttributes {
  bool ids = false;        ///< a std::uint32_t per point
  bool intensity = false;  ///< a float per point
  bool time = false;       ///< seconds per point; needed by max_age_seconds

  [[nodiscard]] bool any() const { return ids || intensity || time; }
};

/// The region the map holds about the sensor, inside the cube of side box_side (which holds the
/// tree). Membership is decided on a held point's stored coordinates minus the sensor's position
/// (both in the precision origin's frame, in double): d, turned into the region's axes by R^T.
enum class RegionShape {
  Cube,        ///< the cube itself, world axes: the paper's region (the default)
  Ball,        ///< |d| <= radius: a LiDAR's reach (KISS-ICP's region)
  OrientedBox  ///< -behind <= x <= ahead, -right <= y <= left, -down <= z <= up in the turned axes
};
/// How an oriented box turns with the sensor (R above).
enum class TurnWith {
  Yaw,  ///< about the world's vertical only, by the sensor's heading: a ground vehicle
  Full  ///< with the sensor's whole orientation: a drone, a hand-held sensor
};

/// Config::region. Whatever its shape the region must fit in the cube in every orientation; a
/// region other than the cube needs InsertPolicy::AllInBox (a turning region takes in scan points
/// the cube held already).
struct Region {
  RegionShape shape = RegionShape::Cube;
  double radius = 0.0;  ///< [m] Ball
  /// [m] OrientedBox, in the sensor's axes (REP 103: x forward, y left, z up)
  double ahead = 0.0, behind = 0.0, left = 0.0, right = 0.0, up = 0.0, down = 0.0;
  TurnWith turn_with = TurnWith::Yaw;  ///< OrientedBox
  /// [s] the region leads the sensor: `ahead` (a ball: `radius`) grows by the sensor's speed
  /// (smoothed over the last frames) times lookahead, up to what the cube holds. It grows at once
  /// to 1.25x what the speed asks and shrinks only once the speed asks for under 1/1.25^2 of it,
  /// so a speed near a threshold does not make it breathe every frame. 0 = a fixed size.
  double lookahead = 0.0;
  /// [s] the time between scans, for the speed, when the scans carry no times (ScanView::times;
  /// with times, the gap between the latest points of two scans): a 10 Hz LiDAR's by default.
  double frame_period = 0.1;
  /// A hard budget of held points; 0 = none. When more would be held after a frame, the region
  /// shrinks about the sensor by one uniform scale, the largest in steps of 1 % at which the held
  /// points fit (nothing held if not even 1 % fits), and each frame starts again from the whole
  /// region, so it grows back as the scene thins.
  std::uint32_t max_points = 0;

  /// [m] the farthest a point of the region lies from the sensor along any world axis, in any
  /// orientation the region can take: what the cube's half side must hold.
  [[nodiscard]] double reach() const;
  /// This region grown by `growth` [m] ahead (a ball: all round), then scaled by `scale` about the
  /// sensor: each extent (extent + growth) * scale.
  [[nodiscard]] Region sized(double growth, double scale) const;
  /// [m] the most the lookahead may grow this region while its reach stays within `half_side`.
  [[nodiscard]] double max_growth(double half_side) const;
};

/// Configuration of an EgoOctree.
struct Config {
  double box_side = 20.0;  ///< L [m]: side of the ego cube held around the sensor; typical 10–100.
  std::uint32_t leaf_capacity = 128;  ///< N_max: a leaf with more points splits; typical 8–128.
  double min_cell_size = 0.05;  ///< [m] cells are never split below this side; typical 0.01–0.5.
  Recentring recentring = Recentring::Quantised;  ///< see Recentring.
  std::uint32_t quantum_levels = 3;  ///< k, Quantised only: q = L / (2^k - 1); range 1–5.
  /// see InsertPolicy: every scan point in the box by default (raw scans); the paper's
  /// ShiftInOnly suits a pre-aggregated map.
  InsertPolicy insert_policy = InsertPolicy::AllInBox;
  DensityCap density_cap{};  ///< optional, off by default.
  std::uint32_t max_age_frames = 0;  ///< drop points inserted more than this many frames ago; 0 = off.
  /// [s] drop points whose time is more than this before the latest time taken in (scan points
  /// too: they are not inserted); 0 = off. Needs attributes.time; not with max_age_frames.
  double max_age_seconds = 0.0;
  KeptAttributes attributes{};  ///< per-point ids, intensities, times; none by default.
  FreeSpaceClearing clearing{};  ///< optional, off by default.
  SensorModel sensor{};  ///< the LiDAR's geometry (free-space clearing); an HDL-64E by default.
  Region region{};  ///< the region held about the sensor; the cube (the paper's) by default.
  /// [m] Quantised only: the voxel size you will ask voxel maps at. The quantum is rounded up to
  /// voxel_size * 2^j, so cells of depth >= k are world voxels of side voxel_size * 2^i and
  /// voxel_keys(voxel_size * 2^i) walks nodes instead of points. 0 = the paper's quantum
  /// L / (2^k - 1); at most box_side.
  double voxel_size = 0.1;

  /// Throws std::invalid_argument naming the field and value when the configuration is unusable.
  void validate() const;

  /// The re-centring quantum [m]: q = L / (2^k - 1) (widened by 1e-9 relative, so the box stays
  /// strictly inside the root cell under rounding), rounded up to voxel_size * 2^j when
  /// voxel_size > 0; 0 in Exact mode.
  [[nodiscard]] double quantum() const;
  /// Side [m] of the root cell: L in Exact mode, q * 2^k (>= L + q) in Quantised mode.
  [[nodiscard]] double root_side() const;
  /// The deepest level a cell may reach: the largest d with root_side / 2^d >= min_cell_size.
  [[nodiscard]] int max_depth() const;
};

}  // namespace eco
