// KITTI's text files: poses.txt, calib.txt and times.txt.

#include <eco/io/kitti.hpp>

#include "io/files.hpp"
#include "io/number_text.hpp"
#include "io/text_cursor.hpp"

#include <Eigen/SVD>

#include <cmath>

namespace eco::io {

namespace {

using detail::TextCursor;

// Twelve numbers, row-major 3x4, into an isometry with an exactly orthonormal rotation.
Eigen::Isometry3d pose_from_words(const TextCursor& cursor, std::span<const std::string_view> words) {
  if (words.size() != 12) {
    cursor.fail("expected 12 numbers (a 3x4 pose, row-major), found " + std::to_string(words.size()));
  }
  Eigen::Matrix<double, 3, 4> m;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) {
      const double value = cursor.number<double>(words[static_cast<std::size_t>(4 * r + c)]);
      if (!std::isfinite(value)) cursor.fail("pose value " + std::to_string(4 * r + c + 1) + " is not finite");
      m(r, c) = value;
    }
  }
  const Eigen::Matrix3d r = m.leftCols<3>();
  const double error = (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (error > 1e-3 || r.determinant() <= 0.0) {
    cursor.fail("the rotation is not a rotation (|R^T R - I| = " + std::to_string(error) +
                ", det = " + std::to_string(r.determinant()) + ")");
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(r, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = svd.matrixU() * svd.matrixV().transpose();  // nearest rotation
  pose.translation() = m.col(3);
  return pose;
}

std::string format_matrix(const Eigen::Isometry3d& pose) {
  std::string line;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) {
      if (!line.empty()) line += ' ';
      detail::append_number(line, pose.matrix()(r, c));
    }
  }
  return line;
}

void require_text(std::string_view text, const std::string& source) {
  if (text.empty()) throw Error(source, "", "is empty");
}

}  // namespace

std::vector<Eigen::Isometry3d> parse_kitti_poses(std::string_view text, const std::string& source) {
  require_text(text, source);
  TextCursor cursor(text, source);
  std::vector<Eigen::Isometry3d> poses;
  while (cursor.next_line()) {
    const auto words = detail::split_words(cursor.line());
    if (words.empty()) continue;
    poses.push_back(pose_from_words(cursor, words));
  }
  if (poses.empty()) throw Error(source, "", "holds no poses");
  return poses;
}

std::vector<Eigen::Isometry3d> read_kitti_poses(const std::filesystem::path& path) {
  return parse_kitti_poses(detail::read_file(path), path.string());
}

std::string format_kitti_pose(const Eigen::Isometry3d& pose) { return format_matrix(pose); }

void write_kitti_poses(const std::filesystem::path& path, std::span<const Eigen::Isometry3d> poses) {
  std::string text;
  for (const auto& pose : poses) text += format_matrix(pose) + '\n';
  detail::write_file(path, text);
}

Eigen::Isometry3d parse_kitti_calib(std::string_view text, const std::string& source) {
  require_text(text, source);
  TextCursor cursor(text, source);
  while (cursor.next_line()) {
    const auto words = detail::split_words(cursor.line());
    if (words.empty() || (words[0] != "Tr:" && words[0] != "Tr_velo_to_cam:")) continue;
    return pose_from_words(cursor, std::span(words).subspan(1));
  }
  throw Error(source, "", "no 'Tr:' line (the velodyne-to-camera transform)");
}

Eigen::Isometry3d read_kitti_calib(const std::filesystem::path& path) {
  return parse_kitti_calib(detail::read_file(path), path.string());
}

void write_kitti_calib(const std::filesystem::path& path, const Eigen::Isometry3d& velo_to_cam) {
  detail::write_file(path, "Tr: " + format_matrix(velo_to_cam) + "\n");
}

std::vector<double> parse_kitti_times(std::string_view text, const std::string& source) {
  require_text(text, source);
  TextCursor cursor(text, source);
  std::vector<double> times;
  while (cursor.next_line()) {
    const auto words = detail::split_words(cursor.line());
    if (words.empty()) continue;
    if (words.size() != 1) cursor.fail("expected one timestamp, found " + std::to_string(words.size()) + " words");
    const double t = cursor.number<double>(words[0]);
    if (!std::isfinite(t)) cursor.fail("timestamp is not finite");
    times.push_back(t);
  }
  return times;
}

std::vector<double> read_kitti_times(const std::filesystem::path& path) {
  return parse_kitti_times(detail::read_file(path), path.string());
}

Eigen::Isometry3d kitti_velo_to_cam() {
  // The `Tr:` line of calib.txt for KITTI odometry sequences 00-02.
  return parse_kitti_calib(
      "Tr: 4.276802385584e-04 -9.999672484946e-01 -8.084491683471e-03 -1.198459927713e-02 "
      "-7.210626507497e-03 8.081198471645e-03 -9.999413164504e-01 -5.403984729748e-02 "
      "9.999738645903e-01 4.859485810390e-04 -7.206933692422e-03 -2.921968648686e-01",
      "built-in KITTI calibration");
}

Eigen::Isometry3d lidar_pose_from_camera(const Eigen::Isometry3d& camera_pose,
                                         const Eigen::Isometry3d& velo_to_cam) {
  return velo_to_cam.inverse() * camera_pose * velo_to_cam;
}

Eigen::Isometry3d camera_pose_from_lidar(const Eigen::Isometry3d& lidar_pose,
                                         const Eigen::Isometry3d& velo_to_cam) {
  return velo_to_cam * lidar_pose * velo_to_cam.inverse();
}

}  // namespace eco::io
