#include "tsgraphs/sim/ray_caster.hpp"

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstring>
#include <stdexcept>

namespace tsgraphs::sim {
namespace {

constexpr int kPacket = 16;
constexpr int kMaxPassThrough = 4;         // glass panes one ray may pass before it counts as lost
constexpr float kPassThroughStep = 1e-3f;  // m beyond a pane where the ray goes on

// A deterministic draw in [0, 1) for a ray meeting a pane: the same scan gives the same
// returns whatever the threads, and neighbouring rays draw independently.
float pass_draw(const Eigen::Vector3f& origin, const Eigen::Vector3f& dir, unsigned prim, int pane) {
  std::uint32_t bits[7];
  std::memcpy(bits, origin.data(), 12);
  std::memcpy(bits + 3, dir.data(), 12);
  bits[6] = prim * 2654435761u + static_cast<std::uint32_t>(pane);
  std::uint64_t h = 0x243F6A8885A308D3ULL;
  for (std::uint32_t b : bits) {
    h ^= b;
    h *= 0x9E3779B97F4A7C15ULL;
    h ^= h >> 29;
  }
  return static_cast<float>(h >> 40) * (1.0f / 16777216.0f);
}

// The floor and the ceiling are one physical slab between storeys; which face a ray meets
// decides the class: from above it is floor, from below ceiling.
std::uint32_t label_for_direction(std::uint32_t label, float dir_z) {
  const auto l = static_cast<PointLabel>(label);
  if (l == PointLabel::kFloor || l == PointLabel::kCeiling) {
    return static_cast<std::uint32_t>(dir_z < 0.0f ? PointLabel::kFloor : PointLabel::kCeiling);
  }
  return label;
}

}  // namespace

BeamPattern BeamPattern::from_sensor(const scene::SensorSpec& sensor) {
  BeamPattern p;
  p.rows = static_cast<int>(sensor.vertical_angles_deg.size());
  p.cols = sensor.columns;
  p.dirs.resize(static_cast<std::size_t>(p.rows) * p.cols);
  for (int r = 0; r < p.rows; ++r) {
    const double el = sensor.vertical_angles_deg[r] * M_PI / 180.0;
    for (int c = 0; c < p.cols; ++c) {
      const double az = 2.0 * M_PI * c / p.cols;
      p.dirs[static_cast<std::size_t>(r) * p.cols + c] =
          Eigen::Vector3d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el))
              .cast<float>();
    }
  }
  return p;
}

struct RayCaster::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<std::uint32_t> labels;
  std::vector<float> transmission;
  bool any_glass = false;

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  // Fills one packet of up to 16 rays starting at column c0 of a row; ray i leaves from
  // origins[i * stride] turned by Rs[i * stride] (stride 0: one pose for the packet).
  void trace_packet(const Eigen::Vector3f* origins, const Eigen::Matrix3f* Rs, int stride,
                    const Eigen::Vector3f* dirs, int n, float min_range, float max_range, RayHit* out) const {
    alignas(64) int valid[kPacket];
    alignas(64) RTCRayHit16 rh;
    Eigen::Vector3f world_dir[kPacket];
    for (int i = 0; i < kPacket; ++i) {
      valid[i] = i < n ? -1 : 0;
      const int at = i < n ? i * stride : 0;
      const Eigen::Vector3f d = i < n ? Eigen::Vector3f(Rs[at] * dirs[i]) : Eigen::Vector3f::UnitX();
      const Eigen::Vector3f& origin = origins[at];
      world_dir[i] = d;
      rh.ray.org_x[i] = origin.x();
      rh.ray.org_y[i] = origin.y();
      rh.ray.org_z[i] = origin.z();
      rh.ray.dir_x[i] = d.x();
      rh.ray.dir_y[i] = d.y();
      rh.ray.dir_z[i] = d.z();
      rh.ray.tnear[i] = 0.0f;
      rh.ray.tfar[i] = max_range;
      rh.ray.time[i] = 0.0f;
      rh.ray.mask[i] = 0xFFFFFFFFu;
      rh.ray.id[i] = static_cast<unsigned>(i);
      rh.ray.flags[i] = 0;
      rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    }
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcIntersect16(valid, scene, &ctx, &rh);
    for (int i = 0; i < n; ++i) {
      // A glass pane lets some rays through: follow them to what lies behind.
      for (int pane = 0; any_glass && pane < kMaxPassThrough && rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
           ++pane) {
        const unsigned prim = rh.hit.primID[i];
        const Eigen::Vector3f origin(rh.ray.org_x[i], rh.ray.org_y[i], rh.ray.org_z[i]);
        if (transmission[prim] <= 0.0f || pass_draw(origin, world_dir[i], prim, pane) >= transmission[prim])
          break;
        RTCRayHit one;
        one.ray.org_x = origin.x();
        one.ray.org_y = origin.y();
        one.ray.org_z = origin.z();
        one.ray.dir_x = world_dir[i].x();
        one.ray.dir_y = world_dir[i].y();
        one.ray.dir_z = world_dir[i].z();
        one.ray.tnear = rh.ray.tfar[i] + kPassThroughStep;
        one.ray.tfar = max_range;
        one.ray.time = 0.0f;
        one.ray.mask = 0xFFFFFFFFu;
        one.ray.id = 0;
        one.ray.flags = 0;
        one.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        one.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        RTCIntersectContext one_ctx;
        rtcInitIntersectContext(&one_ctx);
        rtcIntersect1(scene, &one_ctx, &one);
        rh.hit.geomID[i] = one.hit.geomID;
        rh.hit.primID[i] = one.hit.primID;
        rh.ray.tfar[i] = one.ray.tfar;
        rh.hit.Ng_x[i] = one.hit.Ng_x;
        rh.hit.Ng_y[i] = one.hit.Ng_y;
        rh.hit.Ng_z[i] = one.hit.Ng_z;
      }
      RayHit& h = out[i];
      if (rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID || rh.ray.tfar[i] < min_range) {
        h = RayHit{};
        continue;
      }
      h.range = rh.ray.tfar[i];
      h.label = label_for_direction(labels[rh.hit.primID[i]], world_dir[i].z());
      const Eigen::Vector3f ng(rh.hit.Ng_x[i], rh.hit.Ng_y[i], rh.hit.Ng_z[i]);
      const float norm = ng.norm();
      h.cos_incidence = norm > 0.0f ? std::abs(ng.dot(world_dir[i])) / norm : 0.0f;
    }
  }
};

RayCaster::RayCaster(const LabelledMesh& mesh) : impl_(std::make_unique<Impl>()) {
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) throw std::runtime_error("Embree: cannot create a device");
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
  rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_ROBUST);
  if (!mesh.triangles.empty()) {
    RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                           3 * sizeof(float), mesh.vertices.size()));
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
      vb[3 * i + 0] = mesh.vertices[i].x();
      vb[3 * i + 1] = mesh.vertices[i].y();
      vb[3 * i + 2] = mesh.vertices[i].z();
    }
    auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.triangles.size()));
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
      for (int k = 0; k < 3; ++k) ib[3 * i + k] = static_cast<unsigned>(mesh.triangles[i][k]);
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometry(impl_->scene, geom);
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(impl_->scene);
  impl_->labels = mesh.labels;
  impl_->transmission = mesh.transmission;
  for (float t : mesh.transmission) impl_->any_glass = impl_->any_glass || t > 0.0f;
}

RayCaster::~RayCaster() = default;

void RayCaster::cast_scan(const Pose3& sensor_pose, const BeamPattern& beams, float min_range,
                          float max_range, std::vector<RayHit>* out) const {
  out->resize(beams.dirs.size());
  const Eigen::Vector3f origin = sensor_pose.translation().cast<float>();
  const Eigen::Matrix3f R = sensor_pose.linear().cast<float>();
  tbb::parallel_for(tbb::blocked_range<int>(0, beams.rows), [&](const tbb::blocked_range<int>& rows) {
    for (int r = rows.begin(); r < rows.end(); ++r) {
      const std::size_t row0 = static_cast<std::size_t>(r) * beams.cols;
      for (int c = 0; c < beams.cols; c += kPacket) {
        const int n = std::min(kPacket, beams.cols - c);
        impl_->trace_packet(&origin, &R, 0, &beams.dirs[row0 + c], n, min_range, max_range,
                            &(*out)[row0 + c]);
      }
    }
  });
}

void RayCaster::cast_sweep(const std::vector<Pose3>& column_poses, const BeamPattern& beams, float min_range,
                           float max_range, std::vector<RayHit>* out) const {
  if (column_poses.size() != static_cast<std::size_t>(beams.cols))
    throw std::invalid_argument("RayCaster::cast_sweep: one pose per column");
  out->resize(beams.dirs.size());
  std::vector<Eigen::Vector3f> origins(column_poses.size());
  std::vector<Eigen::Matrix3f> Rs(column_poses.size());
  for (std::size_t c = 0; c < column_poses.size(); ++c) {
    origins[c] = column_poses[c].translation().cast<float>();
    Rs[c] = column_poses[c].linear().cast<float>();
  }
  tbb::parallel_for(tbb::blocked_range<int>(0, beams.rows), [&](const tbb::blocked_range<int>& rows) {
    for (int r = rows.begin(); r < rows.end(); ++r) {
      const std::size_t row0 = static_cast<std::size_t>(r) * beams.cols;
      for (int c = 0; c < beams.cols; c += kPacket) {
        const int n = std::min(kPacket, beams.cols - c);
        impl_->trace_packet(&origins[c], &Rs[c], 1, &beams.dirs[row0 + c], n, min_range, max_range,
                            &(*out)[row0 + c]);
      }
    }
  });
}

RayHit RayCaster::cast(const Eigen::Vector3f& origin, const Eigen::Vector3f& dir, float max_range) const {
  RayHit hit;
  const Eigen::Vector3f d = dir.normalized();
  const Eigen::Matrix3f I = Eigen::Matrix3f::Identity();
  impl_->trace_packet(&origin, &I, 0, &d, 1, 0.0f, max_range, &hit);
  return hit;
}

}  // namespace tsgraphs::sim
