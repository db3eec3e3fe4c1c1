#include <eco/io/transform_tree.hpp>

#include <eco/io/error.hpp>

#include <algorithm>
#include <set>

namespace eco::io {

void TransformTree::add(const StampedTransform& transform, bool is_static, const std::string& source) {
  if (transform.parent.empty() || transform.child.empty() || transform.parent == transform.child) {
    throw Error(source, "", "a transform from '" + transform.parent + "' to '" + transform.child + "' links no two frames");
  }
  const auto [it, added] = links_.try_emplace(transform.child, Link{transform.parent, is_static, {}});
  Link& link = it->second;
  if (link.parent != transform.parent) {
    throw Error(source, "", "frame " + transform.child + " is given two parents, " + link.parent + " and " +
                                transform.parent + ": tf's frames form a tree");
  }
  if (link.is_static != is_static) {
    throw Error(source, "", "the link " + transform.parent + " -> " + transform.child + " is both static and timed");
  }
  if (is_static) {  // the latest static transform holds, as tf2 keeps it
    link.track.poses.assign(1, transform.parent_T_child);
    return;
  }
  // in time order, however the messages came (a recording's /tf is nearly sorted: insertions are at the end)
  const auto at = std::ranges::upper_bound(link.track.times, transform.time);
  const auto offset = at - link.track.times.begin();
  link.track.times.insert(at, transform.time);
  link.track.poses.insert(link.track.poses.begin() + offset, transform.parent_T_child);
}

bool TransformTree::has_frame(const std::string& frame) const {
  if (links_.contains(frame)) return true;
  return std::ranges::any_of(links_, [&](const auto& link) { return link.second.parent == frame; });
}

std::vector<std::string> TransformTree::ancestry(const std::string& frame) const {
  std::vector<std::string> line{frame};
  for (auto it = links_.find(frame); it != links_.end(); it = links_.find(it->second.parent)) {
    if (line.size() > links_.size()) break;  // a loop: refused by add() for a tree, kept finite here anyway
    line.push_back(it->second.parent);
  }
  return line;
}

std::string TransformTree::root_of(const std::string& frame) const { return ancestry(frame).back(); }

std::optional<Eigen::Isometry3d> TransformTree::up_to(const std::string& ancestor, const std::string& frame,
                                                     double time) const {
  Eigen::Isometry3d ancestor_T_frame = Eigen::Isometry3d::Identity();
  for (std::string at = frame; at != ancestor;) {
    const Link& link = links_.at(at);
    const std::optional<Eigen::Isometry3d> step = link.is_static ? link.track.poses.front() : pose_at(link.track, time);
    if (!step) return std::nullopt;
    ancestor_T_frame = *step * ancestor_T_frame;
    at = link.parent;
  }
  return ancestor_T_frame;
}

namespace {

std::string frames_listed(const std::map<std::string, std::string>& parents) {
  std::set<std::string> names;
  for (const auto& [child, parent] : parents) names.insert({child, parent});
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text.empty() ? "none" : text;
}

}  // namespace

std::optional<Eigen::Isometry3d> TransformTree::lookup(const std::string& target, const std::string& source,
                                                       double time) const {
  const std::vector<std::string> up_from_source = ancestry(source), up_from_target = ancestry(target);
  const auto common = std::ranges::find_first_of(up_from_source, up_from_target);
  if (!has_frame(target) || !has_frame(source) || common == up_from_source.end()) {
    std::map<std::string, std::string> parents;
    for (const auto& [child, link] : links_) parents[child] = link.parent;
    throw Error("tf", "", "no chain of transforms joins " + target + " and " + source + "; the frames are: " +
                              frames_listed(parents));
  }
  const std::optional<Eigen::Isometry3d> common_T_source = up_to(*common, source, time);
  const std::optional<Eigen::Isometry3d> common_T_target = up_to(*common, target, time);
  if (!common_T_source || !common_T_target) return std::nullopt;
  return common_T_target->inverse() * *common_T_source;
}

std::string TransformTree::chain(const std::string& target, const std::string& source) const {
  const std::vector<std::string> up_from_source = ancestry(source), up_from_target = ancestry(target);
  const auto common = std::ranges::find_first_of(up_from_source, up_from_target);
  if (common == up_from_source.end()) return target + " .. " + source;
  std::string text;
  for (const std::string& frame : up_from_target) {  // target up to the common frame
    text += (text.empty() ? "" : " <- ") + frame;
    if (frame == *common) break;
  }
  for (auto it = std::make_reverse_iterator(common); it != up_from_source.rend(); ++it) text += " -> " + *it;
  return text;
}

}  // namespace eco::io
