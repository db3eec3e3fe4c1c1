#include <eco/io/pose_file.hpp>

#include <eco/io/kitti.hpp>

#include "io/files.hpp"
#include "io/text_cursor.hpp"

#include <algorithm>
#include <cmath>

namespace eco::io {
namespace {

using detail::TextCursor;

bool is_comment_or_blank(std::string_view line) {
  const auto words = detail::split_words(line);
  return words.empty() || words.front().starts_with('#');
}

PoseTrack parse_tum(std::string_view text, const std::string& source) {
  TextCursor cursor(text, source);
  PoseTrack track;
  while (cursor.next_line()) {
    if (is_comment_or_blank(cursor.line())) continue;
    const auto words = detail::split_words(cursor.line());
    if (words.size() != 8) cursor.fail("expected 8 numbers (TUM: timestamp tx ty tz qx qy qz qw), found " + std::to_string(words.size()));
    double v[8];
    for (std::size_t i = 0; i < 8; ++i) {
      v[i] = cursor.number<double>(words[i]);
      if (!std::isfinite(v[i])) cursor.fail("value " + std::to_string(i + 1) + " is not finite");
    }
    if (!track.times.empty() && v[0] < track.times.back()) {
      cursor.fail("time " + std::string(words[0]) + " goes back from the line before's");
    }
    Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
    if (std::abs(q.norm() - 1.0) > 1e-3) cursor.fail("the quaternion's length is " + std::to_string(q.norm()) + ", not 1");
    track.times.push_back(v[0]);
    track.poses.push_back(pose_of({v[1], v[2], v[3]}, q));
  }
  if (track.poses.empty()) throw Error(source, "", "holds no poses");
  return track;
}

}  // namespace

PoseTrack parse_pose_file(std::string_view text, const std::string& source) {
  TextCursor cursor(text, source);
  while (cursor.next_line()) {
    if (is_comment_or_blank(cursor.line())) continue;
    const std::size_t words = detail::split_words(cursor.line()).size();
    if (words == 12) return {parse_kitti_poses(text, source), {}};
    if (words == 8) return parse_tum(text, source);
    cursor.fail("a pose line of " + std::to_string(words) + " numbers: neither KITTI's 12 nor TUM's 8");
  }
  throw Error(source, "", "holds no poses");
}

Eigen::Isometry3d pose_of(const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = orientation.normalized().toRotationMatrix();
  pose.translation() = position;
  return pose;
}

std::optional<Eigen::Isometry3d> pose_at(const PoseTrack& track, double time) {
  if (!track.timed() || time < track.times.front() || time > track.times.back()) return std::nullopt;
  const auto after = std::ranges::lower_bound(track.times, time);
  const std::size_t b = std::size_t(after - track.times.begin());
  if (track.times[b] == time || b == 0) return track.poses[b];
  const std::size_t a = b - 1;
  const double s = (time - track.times[a]) / (track.times[b] - track.times[a]);
  const Eigen::Quaterniond qa(track.poses[a].linear()), qb(track.poses[b].linear());
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = qa.slerp(s, qb).toRotationMatrix();
  pose.translation() = (1.0 - s) * track.poses[a].translation() + s * track.poses[b].translation();
  return pose;
}

PoseTrack read_pose_file(const std::filesystem::path& path) { return parse_pose_file(detail::read_file(path), path.string()); }

}  // namespace eco::io
