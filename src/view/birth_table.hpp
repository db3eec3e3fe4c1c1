#pragma once
// Where each held position came in, for the recorder: a table from a point's exact coordinates to
// the frame the first point there came in and how many points the last frame and this frame hold
// there. The recorder looks up every held point every frame, so an entry is one 32-byte slot of an
// open-addressing table (linear probing, deletions marked and swept out at the next growth): a
// lookup costs one cache miss, where a node-based map's cost three.

#include <Eigen/Core>

#include <cstdint>
#include <limits>
#include <vector>

namespace eco::view {

class BirthTable {
 public:
  struct Entry {
    double x, y, z;           ///< the position, compared bit for bit
    std::uint32_t frame;      ///< when the first point here came in
    std::uint16_t before;     ///< held here after the last frame (saturating)
    std::uint16_t now;        ///< held here so far this frame (saturating)
  };

  /// The entry at `p` (finite), made with `frame` and no points if there is none.
  Entry& at(const Eigen::Vector3d& p, std::uint32_t frame);

  /// Calls `visit(entry)` on every entry, then forgets the entries no point holds now and makes
  /// this frame's counts the last frame's.
  template <class Visit>
  void end_frame(Visit visit) {
    for (Entry& e : slots_) {
      if (!live(e)) continue;
      visit(static_cast<const Entry&>(e));
      if (e.now == 0) {
        e.x = kDeleted;
        --live_;
      } else {
        e.before = e.now;
        e.now = 0;
      }
    }
  }

  [[nodiscard]] std::size_t size() const { return live_; }

 private:
  static constexpr double kEmpty = -std::numeric_limits<double>::infinity();
  static constexpr double kDeleted = std::numeric_limits<double>::infinity();
  static bool live(const Entry& e) { return e.x != kEmpty && e.x != kDeleted; }
  void grow();

  std::vector<Entry> slots_;
  std::size_t live_ = 0;
  std::size_t used_ = 0;  // live and deleted slots: what probing walks over
};

}  // namespace eco::view
