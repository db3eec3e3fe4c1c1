// The map file's sections, in the order docs/map-format.md lists them.

#include "persist/map_codec.hpp"

#include "bytes/byte_stream.hpp"
#include "bytes/checksum.hpp"
#include "core/geometry/update_arguments.hpp"
#include "core/tree/tree_parts.hpp"

#include <eco/config_fields.hpp>

#include <array>
#include <cmath>
#include <limits>

namespace eco::detail {
namespace {

constexpr std::string_view kMagic{"ECO map\n", 8};
constexpr std::size_t kHeaderBytes = 8 + 4 + 8;  // magic, version, payload length
constexpr std::size_t kChecksumBytes = 4;

// --- the configuration --------------------------------------------------------------------------

// Every field of Config's table (config_fields()) in its order, each as its kind is stored
// (Real: double; Count: uint32; Choice, Switch: one byte, the choice's index); the region's
// fields (region.*) follow the others, and only when the region is not the cube.

bool in_region_section(const ConfigField& field) { return field.name.starts_with("region."); }

/// The file version that first stored `field`.
std::uint32_t stored_since(const ConfigField& field) {
  if (!in_region_section(field)) return kMapFileVersion;
  const bool sized = field.name == "region.lookahead" || field.name == "region.frame_period" ||
                     field.name == "region.max_points";
  return sized ? kMapFileVersionSizedRegion : kMapFileVersionWithRegion;
}

void put_field(ByteWriter& out, const ConfigField& field, const Config& c) {
  const double value = field.get(c);
  switch (field.kind) {
    case ConfigField::Kind::Real: out.put(value); break;
    case ConfigField::Kind::Count: out.put(std::uint32_t(value)); break;
    case ConfigField::Kind::Choice:
    case ConfigField::Kind::Switch: out.put(std::uint8_t(value)); break;
  }
}

void put_config(ByteWriter& out, const Config& c) {
  for (const ConfigField& field : config_fields()) {
    if (!in_region_section(field)) put_field(out, field, c);
  }
  if (c.region.shape == RegionShape::Cube) return;  // version 1: no region section
  for (const ConfigField& field : config_fields()) {
    if (in_region_section(field)) put_field(out, field, c);
  }
}

/// A byte that must be 0 or 1 (a flag).
bool get_flag(ByteReader& in, const char* what) {
  const std::size_t at = in.offset();
  const auto v = in.get<std::uint8_t>(what);
  if (v > 1) ByteReader::fail_at(at, std::string(what) + " = " + std::to_string(v) + " is neither 0 nor 1");
  return v == 1;
}

void get_field(ByteReader& in, const ConfigField& field, Config& c) {
  const std::string name(field.name);
  const std::size_t at = in.offset();
  double value = 0.0;
  switch (field.kind) {
    case ConfigField::Kind::Real: value = in.get<double>(name.c_str()); break;
    case ConfigField::Kind::Count: value = in.get<std::uint32_t>(name.c_str()); break;
    case ConfigField::Kind::Choice:
    case ConfigField::Kind::Switch: {
      const auto index = in.get<std::uint8_t>(name.c_str());
      const bool cube_here = field.name == "region.shape" && index == std::uint8_t(RegionShape::Cube);
      if (index >= field.choices.size() || cube_here) {
        ByteReader::fail_at(at, name + " = " + std::to_string(index) + " is not one of " +
                                    (cube_here ? std::string("ball | oriented_box") : field.range()));
      }
      value = index;
      break;
    }
  }
  field.set(c, value);
}

Config get_config(ByteReader& in, std::uint32_t version) {
  const std::size_t start = in.offset();
  Config c;
  for (const ConfigField& field : config_fields()) {
    if (!in_region_section(field)) get_field(in, field, c);
  }
  if (version >= kMapFileVersionWithRegion) {
    for (const ConfigField& field : config_fields()) {
      if (in_region_section(field) && stored_since(field) <= version) get_field(in, field, c);
    }
  }
  try {
    c.validate();
  } catch (const std::invalid_argument& e) {
    ByteReader::fail_at(start, std::string("configuration: ") + e.what());
  }
  return c;
}

// --- the frame's motion -------------------------------------------------------------------------

void put_pose(ByteWriter& out, const Eigen::Isometry3d& pose) {  // get_pose reads it
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) out.put(pose.matrix()(r, c));
  }
}

/// A pose update() would take under `config` (rigid, where the lattice's integer cells and the
/// density cap's grid reach).
Eigen::Isometry3d get_pose(ByteReader& in, const Config& config) {
  const std::size_t at = in.offset();
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) pose.matrix()(r, c) = in.get<double>("pose");
  }
  try {
    check_update_arguments(pose, "pose", ScanView(), config);
  } catch (const std::invalid_argument& e) {
    ByteReader::fail_at(at, e.what());
  }
  return pose;
}

/// The motion a tree keeps between updates: its pose, precision origin, frame and clock (what
/// the next update starts from; the box follows from them).
void put_motion(ByteWriter& out, const Motion& m) {
  out.put(m.frame);
  if (m.frame == 0) return;
  put_pose(out, m.pose);
  for (int a = 0; a < 3; ++a) out.put(m.anchor[a]);
  out.put(m.clock.latest);
  out.put(m.clock.origin);
  if (!m.region) return;  // version 3: the region's size
  out.put(m.region_size.speed);
  out.put(m.region_size.growth);
  out.put(m.region_size.scale);
  out.put(m.region_size.time);
}

/// The region's size a version-3 file ends its motion with: what the lookahead and the budget
/// could have made of `region` in a cube of half side `half_side`.
RegionSize get_region_size(ByteReader& in, const Region& region, double half_side) {
  const std::size_t at = in.offset();
  RegionSize size;
  size.speed = in.get<double>("region's speed");
  size.growth = in.get<double>("region's growth");
  size.scale = in.get<double>("region's scale");
  size.time = in.get<double>("region's time");
  const bool steps = std::round(size.scale * 100.0) / 100.0 == size.scale;
  if (!(std::isfinite(size.speed) && size.speed >= 0.0 && size.growth >= 0.0 &&
        size.growth <= region.max_growth(half_side) && size.scale >= 0.0 && size.scale <= 1.0 && steps &&
        !std::isinf(size.time))) {
    ByteReader::fail_at(at, "region's size: a speed, growth or scale the region cannot take");
  }
  return size;
}

Motion get_motion(ByteReader& in, const Config& config, std::uint32_t version) {
  Motion m;
  m.frame = in.get<std::uint32_t>("frame");
  if (m.frame == 0) return m;
  m.pose = get_pose(in, config);
  const std::size_t anchor_at = in.offset();
  for (int a = 0; a < 3; ++a) m.anchor[a] = in.get<double>("precision origin");
  const bool steps = (m.anchor.array() / 1024.0).round().matrix() * 1024.0 == m.anchor;
  if (!m.anchor.allFinite() || !steps ||
      precision_origin_for(m.pose.translation(), m.anchor, false) != m.anchor) {
    ByteReader::fail_at(anchor_at, "precision origin: not a multiple of 1024 m near the pose");
  }
  const std::size_t clock_at = in.offset();
  m.clock.latest = in.get<double>("clock.latest");
  m.clock.origin = in.get<double>("clock.origin");
  const bool none = m.clock.latest == -std::numeric_limits<double>::infinity();
  if (!(none ? m.clock.origin == 0.0
             : std::isfinite(m.clock.latest) && std::isfinite(m.clock.origin) &&
                   std::floor(m.clock.origin / 64.0) * 64.0 == m.clock.origin)) {
    ByteReader::fail_at(clock_at, "clock: its latest time and origin do not fit together");
  }
  m.box = ego_box(m.pose.translation(), m.anchor, config.box_side);
  if (version >= kMapFileVersionSizedRegion) m.region_size = get_region_size(in, config.region, config.box_side / 2);
  m.region = EgoRegion::at(config.region, m.region_size, m.pose, m.anchor);
  return m;
}

// --- the tree -----------------------------------------------------------------------------------

void put_tree(ByteWriter& out, const TreeLayout& layout) {
  out.put(std::uint64_t(layout.nodes.size()));
  for (const NodeEntry& n : layout.nodes) {
    out.put(std::uint8_t(n.leaf ? 0 : 1));
    if (n.leaf) {
      out.put(n.count);
    } else {
      out.put(n.children);
    }
  }
  out.put(std::uint64_t(layout.point_count));
  // each column whole, gathered leaf by leaf from where the tree holds it
  const auto column = [&](auto column_of) {
    for (const PointSpan& leaf : layout.leaves) {
      const auto* values = column_of(leaf);  // null: a column the tree does not keep, or no points
      if (values != nullptr) out.put_bytes({reinterpret_cast<const char*>(values), leaf.size * sizeof(values[0])});
    }
  };
  column([](const PointSpan& s) { return s.x; });
  column([](const PointSpan& s) { return s.y; });
  column([](const PointSpan& s) { return s.z; });
  column([](const PointSpan& s) { return s.stamps; });
  column([](const PointSpan& s) { return s.ids; });
  column([](const PointSpan& s) { return s.intensities; });
  column([](const PointSpan& s) { return s.times; });
}

/// The tree of the nodes and points sections, its points read where they lie in the file's bytes.
std::unique_ptr<Tree> get_tree(ByteReader& in, const Config& config, const Motion& motion) {
  TreeParts parts;
  parts.motion = motion;
  const std::size_t nodes_at = in.offset();
  const auto m = in.get<std::uint64_t>("node count");
  if (m > in.left() / 2) ByteReader::fail_at(nodes_at, "node count " + std::to_string(m) + ": past the end of the file");
  parts.nodes.resize(m);
  for (NodeEntry& n : parts.nodes) {
    n.leaf = !get_flag(in, "node kind");
    if (n.leaf) {
      n.count = in.get<std::uint32_t>("leaf point count");
    } else {
      n.children = in.get<std::uint8_t>("inner node's children");
    }
  }
  const auto n = in.get<std::uint64_t>("point count");  // get_in_place refuses a count past the file
  parts.point_count = n;
  for_each_column(parts.points, kept_columns(config), [&](const std::byte*& values, bool is_kept, const char* what) {
    if (is_kept) values = in.get_in_place<std::uint32_t>(n, what);  // every column: 4-byte values
  });
  try {
    return std::make_unique<Tree>(config, parts);
  } catch (const std::invalid_argument& e) {
    ByteReader::fail_at(nodes_at, std::string("tree: ") + e.what());
  }
}

// --- free-space clearing ------------------------------------------------------------------------

/// The last update's range image (its frame and pose are the tree's) and the arrivals that leave
/// at the next update.
void put_clearing(ByteWriter& out, const ClearingState& state, const Tree& tree) {
  const SensorModel& sensor = tree.config().sensor;
  const std::size_t pixels = state.image.frame == 0 ? 0 : std::size_t(sensor.rows()) * std::size_t(sensor.columns());
  out.put(std::uint64_t(pixels));
  out.put_bytes({reinterpret_cast<const char*>(state.image.storage.data()), pixels * sizeof(double)});
  out.put(std::uint64_t(state.leaving.size()));
  for (const StoredPoint& s : state.leaving) {
    for (const float v : s.p) out.put(v);
    out.put(s.stamp);
    out.put(s.id);
    out.put(s.intensity);
    out.put(s.time);
  }
}

std::unique_ptr<ClearingState> get_clearing(ByteReader& in, const Tree& tree) {
  auto state = std::make_unique<ClearingState>();
  const std::size_t image_at = in.offset();
  const SensorModel& sensor = tree.config().sensor;  // (the pixel lookup's tables are built when first used)
  const std::size_t expected = tree.motion().frame == 0 ? 0 : std::size_t(sensor.rows()) * std::size_t(sensor.columns());
  state->image.storage = in.get_array<double>("range image");
  if (state->image.storage.size() != expected) {
    ByteReader::fail_at(image_at, "range image of " + std::to_string(state->image.storage.size()) +
                                      " pixels, where the sensor model has " + std::to_string(expected));
  }
  if (expected > 0) {
    state->image.frame = tree.motion().frame;
    state->image.pose = tree.motion().pose;
  }
  const std::size_t leaving_at = in.offset();
  const auto n = in.get<std::uint64_t>("arrivals count");
  if (n > in.left() / 28) ByteReader::fail_at(leaving_at, "arrivals count " + std::to_string(n) + ": past the end of the file");
  state->leaving.resize(n);
  for (StoredPoint& s : state->leaving) {
    for (float& v : s.p) v = in.get<float>("arrival");
    s.stamp = in.get<std::uint32_t>("arrival");
    s.id = in.get<std::uint32_t>("arrival");
    s.intensity = in.get<float>("arrival");
    s.time = in.get<float>("arrival");
  }
  return state;
}

}  // namespace

std::string encode_map(const Tree& tree, const ClearingState* clearing) {
  const TreeLayout layout = layout_of(tree);
  ByteWriter out;
  const std::size_t columns = 3 + std::size_t(tree.points().columns().count());
  const std::size_t image = clearing ? clearing->image.storage.size() * sizeof(double) : 0;
  // room for it all at once: the points are most of it, and growing would copy them
  out.bytes().reserve(1024 + 5 * layout.nodes.size() + 4 * columns * layout.point_count + image);
  out.put_bytes(kMagic);
  out.put(tree.config().region.shape == RegionShape::Cube ? kMapFileVersion : kMapFileVersionSizedRegion);
  out.put(std::uint64_t(0));  // the payload's length, once known
  put_config(out, tree.config());
  put_motion(out, tree.motion());
  put_tree(out, layout);
  if (tree.config().clearing.enabled) put_clearing(out, *clearing, tree);
  std::string& bytes = out.bytes();
  const std::uint64_t payload = bytes.size() - kHeaderBytes;
  std::memcpy(bytes.data() + 12, &payload, sizeof(payload));
  const std::uint32_t crc = checksum(bytes);
  bytes.append(reinterpret_cast<const char*>(&crc), sizeof(crc));
  return std::move(bytes);
}

DecodedMap decode_map(std::string_view bytes) {
  ByteReader header(bytes);
  for (const char expected : kMagic) {
    if (header.get<char>("magic") != expected) ByteReader::fail_at(0, "not a map file (wrong magic)");
  }
  const auto version = header.get<std::uint32_t>("version");
  if (version < kMapFileVersion || version > kMapFileVersionSizedRegion) {
    ByteReader::fail_at(8, "version " + std::to_string(version) + "; this library reads versions " +
                               std::to_string(kMapFileVersion) + " to " + std::to_string(kMapFileVersionSizedRegion));
  }
  const auto payload = header.get<std::uint64_t>("payload length");
  if (bytes.size() < kHeaderBytes + kChecksumBytes) {
    ByteReader::fail_at(bytes.size(), "the file ends before its checksum (truncated)");
  }
  const std::size_t held = bytes.size() - kHeaderBytes - kChecksumBytes;
  if (payload != held) {
    ByteReader::fail_at(12, "payload of " + std::to_string(payload) + " bytes, where the file holds " +
                                std::to_string(held) + " (truncated or extended)");
  }
  const std::size_t end = kHeaderBytes + held;
  std::uint32_t stored = 0;
  std::memcpy(&stored, bytes.data() + end, sizeof(stored));
  if (checksum(bytes.substr(0, end)) != stored) ByteReader::fail_at(end, "checksum mismatch: the file is corrupted");

  ByteReader in(bytes.substr(0, end), kHeaderBytes);
  const Config config = get_config(in, version);
  const Motion motion = get_motion(in, config, version);
  DecodedMap map;
  map.tree = get_tree(in, config, motion);
  if (config.clearing.enabled) map.clearing = get_clearing(in, *map.tree);
  if (in.left() != 0) in.fail(std::to_string(in.left()) + " bytes past the map");
  return map;
}

}  // namespace eco::detail
