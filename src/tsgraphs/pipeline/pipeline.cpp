#include "tsgraphs/pipeline/pipeline.hpp"

#include <chrono>
#include <cmath>
#include <map>
#include <stdexcept>

#include "tsgraphs/walls/plane_extraction.hpp"

namespace tsgraphs::pipeline {
namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

Pipeline::Pipeline(PipelineConfig config)
    : config_(std::move(config)),
      selector_(config_.keyframes),
      mapper_(config_.plane_mapping),
      optimizer_(config_.optimizer),
      loop_detector_(config_.loop_closure) {}

const ScanRecord& Pipeline::process(std::size_t scan_index, double stamp, const PointCloud& scan, const Pose3& odom) {
  if (!odom.matrix().allFinite() || !std::isfinite(stamp))
    throw std::invalid_argument("scan " + std::to_string(scan_index) + ": non-finite pose or time");
  const auto start = std::chrono::steady_clock::now();
  ScanRecord record;
  record.scan_index = scan_index;
  record.stamp = stamp;
  record.odom = odom;
  if (last_odom_) accum_distance_ += (last_odom_->translation() - odom.translation()).norm();
  last_odom_ = odom;

  PointCloud cloud = prefilter(scan, config_.prefilter);
  record.num_points = cloud.size();
  record.prefilter_ms = ms_since(start);
  record.reference_keyframe = graph_.keyframes().empty() ? -1 : static_cast<int>(graph_.keyframes().size()) - 1;

  if (selector_.is_keyframe(odom)) {
    if (cloud.empty()) {
      record.warning = scan.empty() ? "empty scan: skipped" : "no point left after prefiltering: skipped";
    } else {
      selector_.accept(odom);
      add_keyframe(record, std::move(cloud));
    }
  } else if (scan.empty()) {
    record.warning = "empty scan: skipped";
  }
  record.frontend_ms = ms_since(start);
  scans_.push_back(record);
  // The back-end runs after the front-end bookkeeping so that frontend_ms excludes it.
  if (record.keyframe >= 0) {
    const bool loop = !graph_.loop_edges().empty() && graph_.loop_edges().back().to == record.keyframe;
    ++keyframes_since_solve_;
    ++keyframes_since_full_;
    if (loop) {
      optimize(true, "loop");
    } else if (config_.schedule.full_every_keyframes > 0 &&
               keyframes_since_full_ >= config_.schedule.full_every_keyframes) {
      optimize(true, "periodic");
    } else if (keyframes_since_solve_ >= config_.schedule.optimize_every_keyframes) {
      optimize(false, "schedule");
    }
  }
  return scans_.back();
}

void Pipeline::add_keyframe(ScanRecord& record, PointCloud cloud) {
  graph::KeyframeNode node;
  node.scan_index = record.scan_index;
  node.stamp = record.stamp;
  node.odom = record.odom;
  node.accum_distance = accum_distance_;
  if (graph_.keyframes().empty()) {
    node.pose = record.odom;  // the map frame is the odometry frame at the first keyframe
  } else {
    const graph::KeyframeNode& last = graph_.keyframes().back();
    node.pose = last.pose * (last.odom.inverse() * record.odom);
  }
  const int id = graph_.add_keyframe(node);
  if (id > 0) {
    const graph::KeyframeNode& prev = graph_.keyframes()[id - 1];
    graph_.add_odometry_edge({id - 1, id, prev.odom.inverse() * record.odom, 0.0});
  }
  record.keyframe = id;
  record.reference_keyframe = id;
  keyframe_clouds_.push_back(std::move(cloud));

  // Walls (and floor/ceiling planes): extract, associate or create, add the factors.
  const auto walls_start = std::chrono::steady_clock::now();
  const Pose3& T = graph_.keyframes()[id].pose;
  const auto observations = walls::extract_planes(keyframe_clouds_.back(), T.linear(), config_.plane_extraction);
  for (const walls::PlaneObservation& obs : observations) {
    int plane_id = mapper_.associate(obs, T);
    if (plane_id < 0) {
      plane_id = graph_.add_plane(obs.plane.transformed(T), obs.vertical);
      mapper_.add_landmark(plane_id, obs, T, id);
    } else {
      mapper_.add_observation(plane_id, obs, T, id);
    }
    graph_.add_plane_edge({id, plane_id, obs.plane, obs.num_inliers});
  }
  record.walls_ms = ms_since(walls_start);

  const auto loop_start = std::chrono::steady_clock::now();
  if (auto loop = loop_detector_.detect(graph_, id, [this](int k) -> const PointCloud& { return keyframe_clouds_[k]; }))
    graph_.add_loop_edge(*loop);
  record.loop_ms = ms_since(loop_start);
}

void Pipeline::optimize(bool full, const std::string& reason) {
  if (graph_.keyframes().size() < 2) return;
  OptimizationRecord rec;
  rec.after_keyframe = static_cast<int>(graph_.keyframes().size()) - 1;
  rec.reason = reason;
  rec.stats = optimizer_.optimize(graph_, full);
  optimizations_.push_back(rec);
  keyframes_since_solve_ = 0;
  if (full) keyframes_since_full_ = 0;

  std::map<int, Plane> planes;
  for (const auto& [id, node] : graph_.planes()) planes.emplace(id, node.plane);
  const auto pose_of = [this](int k) { return graph_.keyframes().at(k).pose; };
  mapper_.update(planes, pose_of);
  if (config_.schedule.merge_duplicate_planes) {
    for (const auto& [keep, drop] : mapper_.find_duplicates()) {
      if (!graph_.planes().count(keep) || !graph_.planes().count(drop)) continue;
      graph_.merge_planes(keep, drop);
      mapper_.merge(keep, drop, pose_of);
    }
  }
}

void Pipeline::finish() {
  if (graph_.keyframes().size() >= 2) optimize(true, "final");
}

std::vector<Pose3> Pipeline::trajectory() const {
  std::vector<Pose3> poses;
  poses.reserve(scans_.size());
  for (const ScanRecord& s : scans_) {
    if (s.reference_keyframe < 0) {
      poses.push_back(s.odom);  // before the first keyframe: the map frame is the odometry frame
      continue;
    }
    const graph::KeyframeNode& kf = graph_.keyframes()[s.reference_keyframe];
    poses.push_back(kf.pose * (kf.odom.inverse() * s.odom));
  }
  return poses;
}

}  // namespace tsgraphs::pipeline
