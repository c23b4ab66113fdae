#include "tsgraphs/ros2_bag/ros2_messages.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/ros2_bag/cdr.hpp"

namespace tsgraphs::ros2_bag::ros2 {
namespace {

// Each type's fields (ros2msg), and the types it uses, by "package/Type".
const std::map<std::string, std::string>& field_texts() {
  static const std::map<std::string, std::string> kTexts = {
      {"builtin_interfaces/Time", "int32 sec\nuint32 nanosec\n"},
      {"std_msgs/Header", "builtin_interfaces/Time stamp\nstring frame_id\n"},
      {"sensor_msgs/PointField", "string name\nuint32 offset\nuint8 datatype\nuint32 count\n"},
      {"sensor_msgs/PointCloud2",
       "std_msgs/Header header\nuint32 height\nuint32 width\nsensor_msgs/PointField[] fields\nbool "
       "is_bigendian\n"
       "uint32 point_step\nuint32 row_step\nuint8[] data\nbool is_dense\n"},
      {"geometry_msgs/Point", "float64 x\nfloat64 y\nfloat64 z\n"},
      {"geometry_msgs/Vector3", "float64 x\nfloat64 y\nfloat64 z\n"},
      {"geometry_msgs/Quaternion", "float64 x\nfloat64 y\nfloat64 z\nfloat64 w\n"},
      {"geometry_msgs/Pose", "geometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n"},
      {"geometry_msgs/PoseWithCovariance", "geometry_msgs/Pose pose\nfloat64[36] covariance\n"},
      {"geometry_msgs/Twist", "geometry_msgs/Vector3 linear\ngeometry_msgs/Vector3 angular\n"},
      {"geometry_msgs/TwistWithCovariance", "geometry_msgs/Twist twist\nfloat64[36] covariance\n"},
      {"geometry_msgs/PoseStamped", "std_msgs/Header header\ngeometry_msgs/Pose pose\n"},
      {"geometry_msgs/Transform", "geometry_msgs/Vector3 translation\ngeometry_msgs/Quaternion rotation\n"},
      {"geometry_msgs/TransformStamped",
       "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/Transform transform\n"},
      {"nav_msgs/Odometry",
       "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/PoseWithCovariance pose\n"
       "geometry_msgs/TwistWithCovariance twist\n"},
      {"tf2_msgs/TFMessage", "geometry_msgs/TransformStamped[] transforms\n"},
  };
  return kTexts;
}

// "pkg/msg/Type" -> "pkg/Type".
std::string short_name(const std::string& type) {
  const auto at = type.find("/msg/");
  return at == std::string::npos ? type : type.substr(0, at) + type.substr(at + 4);
}

// The (type, name) of each field of a definition's first section; types without package and
// array bounds, so that "Header header" and "std_msgs/Header header" agree.
std::vector<std::pair<std::string, std::string>> fields_of(const std::string& text) {
  std::vector<std::pair<std::string, std::string>> out;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("====", 0) == 0) break;  // the first dependency
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    std::string type, name;
    if (!(words >> type >> name)) continue;
    if (name.find('=') != std::string::npos) continue;  // a constant: NAME=value
    std::string rest;
    if (words >> rest && rest[0] == '=') continue;  // a constant written NAME = value
    type = type.substr(type.rfind('/') == std::string::npos ? 0 : type.rfind('/') + 1);
    type = type.substr(0, type.find('['));
    out.emplace_back(type, name);
  }
  return out;
}

double stamp_of(CdrReader& r) {
  const std::int32_t sec = r.i32("header.stamp.sec");
  const std::uint32_t nanosec = r.u32("header.stamp.nanosec");
  return static_cast<double>(sec) + 1e-9 * static_cast<double>(nanosec);
}

void put_header(CdrWriter& w, double stamp, const std::string& frame_id) {
  const std::uint64_t ns = stamp_nanoseconds(stamp);
  w.i32(static_cast<std::int32_t>(ns / 1000000000ull));
  w.u32(static_cast<std::uint32_t>(ns % 1000000000ull));
  w.string(frame_id);
}

// position and orientation (x y z w) as a pose; a non-finite value or a zero quaternion is an
// InputError naming the message.
Pose3 read_pose(CdrReader& r, const std::string& where, const char* position, const char* orientation) {
  Eigen::Vector3d t;
  for (int i = 0; i < 3; ++i) t[i] = r.f64(position);
  double q[4];
  for (double& v : q) v = r.f64(orientation);
  const Eigen::Quaterniond quat(q[3], q[0], q[1], q[2]);
  if (!t.allFinite() || !quat.coeffs().allFinite() || quat.norm() < 1e-6) {
    throw input_error(where, 0,
                      std::string(orientation) + " or " + position + " is not finite, or not a rotation");
  }
  Pose3 pose = Pose3::Identity();
  pose.linear() = quat.normalized().toRotationMatrix();
  pose.translation() = t;
  return pose;
}

void put_pose(CdrWriter& w, const Pose3& pose) {
  for (int i = 0; i < 3; ++i) w.f64(pose.translation()[i]);
  const Eigen::Quaterniond q(pose.linear());
  w.f64(q.x()), w.f64(q.y()), w.f64(q.z()), w.f64(q.w());
}

}  // namespace

std::uint64_t stamp_nanoseconds(double t) {
  const auto sec = static_cast<std::uint64_t>(std::floor(t));
  const auto nsec = static_cast<std::uint64_t>(std::llround((t - static_cast<double>(sec)) * 1e9));
  return sec * 1000000000ull + nsec;  // a nanosecond part rounded to 1e9 carries into the seconds
}

const std::string& definition(const std::string& type) {
  static const std::map<std::string, std::string> kDefinitions = [] {
    std::map<std::string, std::string> out;
    const auto& texts = field_texts();
    for (const char* top : {kPointCloud2, kOdometry, kPoseStamped, kTfMessage}) {
      // The type's own fields, then every type it uses, depth first, each once.
      std::string text = texts.at(short_name(top));
      std::vector<std::string> seen{short_name(top)}, pending{short_name(top)};
      while (!pending.empty()) {
        const std::string t = pending.back();
        pending.pop_back();
        std::vector<std::string> used;
        std::istringstream lines(texts.at(t));
        for (std::string line; std::getline(lines, line);) {
          std::string field_type = line.substr(0, line.find(' '));
          field_type = field_type.substr(0, field_type.find('['));
          if (field_type.find('/') != std::string::npos &&
              std::find(seen.begin(), seen.end(), field_type) == seen.end()) {
            seen.push_back(field_type);
            used.push_back(field_type);
            text += "\n" + std::string(80, '=') + "\nMSG: " + field_type + "\n" + texts.at(field_type);
          }
        }
        pending.insert(pending.end(), used.rbegin(), used.rend());
      }
      out[top] = text;
    }
    return out;
  }();
  const auto it = kDefinitions.find(type);
  if (it == kDefinitions.end()) throw std::invalid_argument("ros2::definition: no definition of " + type);
  return it->second;
}

std::string definition_mismatch(const std::string& type, const std::string& text) {
  if (text.empty()) return "";
  const auto expected = fields_of(definition(type));
  const auto recorded = fields_of(text);
  if (recorded == expected) return "";
  const auto list = [](const std::vector<std::pair<std::string, std::string>>& f) {
    std::string s;
    for (const auto& [t, n] : f) s += (s.empty() ? "" : ", ") + t + " " + n;
    return s;
  };
  return "its definition declares (" + list(recorded) + "), not the fields of " + type + " (" +
         list(expected) + ")";
}

io::PointCloud2Message parse_point_cloud2(const std::string& cdr, const std::string& where) {
  CdrReader r(cdr, where);
  io::PointCloud2Message m;
  m.stamp = stamp_of(r);
  m.frame_id = r.string("header.frame_id");
  m.layout.height = r.u32("height");
  m.layout.width = r.u32("width");
  // A field is at least a name (length and NUL), an offset, a datatype and a count.
  const std::uint32_t n = r.sequence("fields", 4 + 1 + 4 + 1 + 4);
  for (std::uint32_t i = 0; i < n; ++i) {
    io::PointField2 f;
    f.name = r.string("fields[].name");
    f.offset = r.u32("fields[].offset");
    f.datatype = r.u8("fields[].datatype");
    f.count = r.u32("fields[].count");
    m.layout.fields.push_back(f);
  }
  m.layout.is_bigendian = r.boolean("is_bigendian");
  m.layout.point_step = r.u32("point_step");
  m.layout.row_step = r.u32("row_step");
  m.data_size = r.sequence("data", 1);
  m.data_offset = r.skip(m.data_size, "data");
  r.boolean("is_dense");
  return m;
}

StampedPoseMessage parse_odometry(const std::string& cdr, const std::string& where) {
  CdrReader r(cdr, where);
  StampedPoseMessage m;
  m.stamp = stamp_of(r);
  m.frame_id = r.string("header.frame_id");
  m.child_frame_id = r.string("child_frame_id");
  m.pose = read_pose(r, where, "pose.pose.position", "pose.pose.orientation");
  for (int i = 0; i < 36; ++i) r.f64("pose.covariance");
  for (int i = 0; i < 6 + 36; ++i) r.f64("twist");
  return m;
}

StampedPoseMessage parse_pose_stamped(const std::string& cdr, const std::string& where) {
  CdrReader r(cdr, where);
  StampedPoseMessage m;
  m.stamp = stamp_of(r);
  m.frame_id = r.string("header.frame_id");
  m.pose = read_pose(r, where, "pose.position", "pose.orientation");
  return m;
}

std::vector<TransformMessage> parse_tf_message(const std::string& cdr, const std::string& where) {
  CdrReader r(cdr, where);
  // A transform is at least a header (8 + 5), a child frame (5) and 7 doubles.
  const std::uint32_t n = r.sequence("transforms", 8 + 5 + 5 + 7 * 8);
  std::vector<TransformMessage> out;
  for (std::uint32_t i = 0; i < n; ++i) {
    TransformMessage t;
    t.stamp = stamp_of(r);
    t.parent = r.string("transforms[].header.frame_id");
    t.child = r.string("transforms[].child_frame_id");
    t.transform =
        read_pose(r, where, "transforms[].transform.translation", "transforms[].transform.rotation");
    out.push_back(std::move(t));
  }
  return out;
}

std::string encode_point_cloud2(double stamp, const std::string& frame_id, const PointCloud& cloud) {
  CdrWriter w;
  put_header(w, stamp, frame_id);
  const auto n = static_cast<std::uint32_t>(cloud.size());
  w.u32(1), w.u32(n);
  const bool timed = cloud.has_times();
  const std::uint32_t fields = timed ? 5 : 4;
  w.sequence(fields);
  const char* const names[] = {"x", "y", "z", "intensity", "time"};
  for (std::uint32_t i = 0; i < fields; ++i) {
    w.string(names[i]);
    w.u32(4 * i), w.u8(static_cast<std::uint8_t>(io::FieldType::float32)), w.u32(1);
  }
  w.boolean(false);
  const std::uint32_t point_step = 4 * fields;
  w.u32(point_step), w.u32(point_step * n);
  w.sequence(point_step * n);
  std::string data(static_cast<std::size_t>(point_step) * n, '\0');
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const float v[5] = {cloud.points[i].x(), cloud.points[i].y(), cloud.points[i].z(),
                        cloud.has_intensity() ? cloud.intensity[i] : 0.0f, timed ? cloud.times[i] : 0.0f};
    std::memcpy(data.data() + point_step * i, v, point_step);  // little-endian hosts (x86, ARM)
  }
  w.raw(data);
  w.boolean(true);
  return w.bytes();
}

std::string encode_odometry(const StampedPoseMessage& m) {
  CdrWriter w;
  put_header(w, m.stamp, m.frame_id);
  w.string(m.child_frame_id);
  put_pose(w, m.pose);
  for (int i = 0; i < 36 + 6 + 36; ++i) w.f64(0.0);  // covariance, twist, its covariance
  return w.bytes();
}

std::string encode_pose_stamped(const StampedPoseMessage& m) {
  CdrWriter w;
  put_header(w, m.stamp, m.frame_id);
  put_pose(w, m.pose);
  return w.bytes();
}

std::string encode_tf_message(const std::vector<TransformMessage>& transforms) {
  CdrWriter w;
  w.sequence(static_cast<std::uint32_t>(transforms.size()));
  for (const TransformMessage& t : transforms) {
    put_header(w, t.stamp, t.parent);
    w.string(t.child);
    put_pose(w, t.transform);
  }
  return w.bytes();
}

}  // namespace tsgraphs::ros2_bag::ros2
