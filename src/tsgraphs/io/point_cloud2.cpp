#include "tsgraphs/io/point_cloud2.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/printable.hpp"
#include "tsgraphs/io/point_time.hpp"

namespace tsgraphs::io {

namespace {

std::size_t size_of(std::uint8_t datatype) {
  switch (static_cast<FieldType>(datatype)) {
    case FieldType::int8:
    case FieldType::uint8:
      return 1;
    case FieldType::int16:
    case FieldType::uint16:
      return 2;
    case FieldType::int32:
    case FieldType::uint32:
    case FieldType::float32:
      return 4;
    case FieldType::float64:
      return 8;
  }
  return 0;
}

template <class T>
double load(const std::uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return static_cast<double>(v);
}

/// The value of a field of any datatype as a double.
double value_of(const PointField2& f, const std::uint8_t* point) {
  const std::uint8_t* p = point + f.offset;
  switch (static_cast<FieldType>(f.datatype)) {
    case FieldType::int8:
      return load<std::int8_t>(p);
    case FieldType::uint8:
      return load<std::uint8_t>(p);
    case FieldType::int16:
      return load<std::int16_t>(p);
    case FieldType::uint16:
      return load<std::uint16_t>(p);
    case FieldType::int32:
      return load<std::int32_t>(p);
    case FieldType::uint32:
      return load<std::uint32_t>(p);
    case FieldType::float32:
      return load<float>(p);
    case FieldType::float64:
      return load<double>(p);
  }
  return 0.0;
}

/// The bytes a field takes in a point: its values (a count of 0 read as 1, as everywhere here).
std::size_t extent_of(const PointField2& f) {
  return size_of(f.datatype) * std::max<std::uint32_t>(f.count, 1);
}

/// Fields must not share bytes: x a float64 at 0 with y at 4 would decode y from half of x, as
/// garbage and without a word. Checked once per message, on fields already known to fit.
void check_fields_apart(const std::vector<PointField2>& fields, const std::string& where) {
  std::vector<const PointField2*> by_offset;
  for (const PointField2& f : fields) by_offset.push_back(&f);
  std::stable_sort(by_offset.begin(), by_offset.end(),
                   [](const PointField2* a, const PointField2* b) { return a->offset < b->offset; });
  const PointField2* reaching = nullptr;  // of the fields so far, the one ending last
  for (const PointField2* f : by_offset) {
    if (reaching && f->offset < reaching->offset + extent_of(*reaching)) {
      const auto bytes = [](const PointField2& g) {
        return "bytes " + std::to_string(g.offset) + " to " + std::to_string(g.offset + extent_of(g) - 1);
      };
      throw input_error(where, 0,
                        "field '" + printable(f->name) + "' (" + bytes(*f) + ") overlaps field '" +
                            printable(reaching->name) + "' (" + bytes(*reaching) + ")");
    }
    if (!reaching || f->offset + extent_of(*f) > reaching->offset + extent_of(*reaching)) reaching = f;
  }
}

}  // namespace

PointCloud decode_point_cloud2(const PointCloud2Layout& layout, const std::uint8_t* data, std::size_t size,
                               const std::string& where) {
  if (layout.is_bigendian) throw input_error(where, 0, "big-endian point data is not supported");
  std::optional<PointField2> x, y, z, intensity, time;
  double time_scale = 0.0;
  std::size_t time_rank = time_field_names().size();
  for (const PointField2& f : layout.fields) {
    const std::size_t bytes = size_of(f.datatype);
    if (bytes == 0)
      throw input_error(where, 0,
                        "field '" + f.name + "' has unknown datatype " + std::to_string(f.datatype));
    if (f.offset + extent_of(f) > layout.point_step)
      throw input_error(where, 0,
                        "field '" + f.name + "' ends past point_step " + std::to_string(layout.point_step));
    if (f.name == "x") x = f;
    if (f.name == "y") y = f;
    if (f.name == "z") z = f;
    if (f.name == "intensity") intensity = f;
    const auto scale =
        time_field_scale(f.name, f.datatype != static_cast<std::uint8_t>(FieldType::float32) &&
                                     f.datatype != static_cast<std::uint8_t>(FieldType::float64));
    const auto rank = static_cast<std::size_t>(
        std::find(time_field_names().begin(), time_field_names().end(), f.name) - time_field_names().begin());
    if (scale && rank < time_rank) {
      time = f;
      time_scale = *scale;
      time_rank = rank;
    }
  }
  check_fields_apart(layout.fields, where);
  if (!x || !y || !z) throw input_error(where, 0, "no x, y and z fields");
  for (const PointField2* f : {&*x, &*y, &*z}) {
    if (f->datatype != static_cast<std::uint8_t>(FieldType::float32) &&
        f->datatype != static_cast<std::uint8_t>(FieldType::float64))
      throw input_error(where, 0, "coordinate '" + f->name + "' is neither float32 nor float64");
  }
  const std::size_t rows = layout.height, columns = layout.width;
  if (layout.row_step < columns * layout.point_step)
    throw input_error(where, 0,
                      "row_step " + std::to_string(layout.row_step) + " shorter than width x point_step");
  if (size < rows * layout.row_step)
    throw input_error(where, 0,
                      "data has " + std::to_string(size) + " bytes, height x row_step needs " +
                          std::to_string(rows * layout.row_step));
  PointCloud cloud;
  if (rows == 0 || columns == 0) return cloud;  // no point, however many empty rows it claims
  cloud.reserve(rows * columns, intensity.has_value(), false);
  std::vector<double> seconds;
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < columns; ++c) {
      const std::uint8_t* point = data + r * layout.row_step + c * layout.point_step;
      const double px = value_of(*x, point), py = value_of(*y, point), pz = value_of(*z, point);
      if (!std::isfinite(px) || !std::isfinite(py) || !std::isfinite(pz)) continue;  // no return
      cloud.points.emplace_back(static_cast<float>(px), static_cast<float>(py), static_cast<float>(pz));
      if (intensity) cloud.intensity.push_back(static_cast<float>(value_of(*intensity, point)));
      if (time) {
        const double t = value_of(*time, point) * time_scale;
        if (!std::isfinite(t))
          throw input_error(where, 0,
                            "point " + std::to_string(cloud.size() - 1) + ": field '" + time->name +
                                "' is not a finite number");
        seconds.push_back(t);
      }
    }
  }
  if (time) cloud.times = relative_times(seconds);
  return cloud;
}

namespace {

// The smallest serialized sensor_msgs/PointField: an empty name's length word, offset (4),
// datatype (1) and count (4). A field count is checked against it before anything is reserved.
constexpr std::size_t kMinSerializedFieldBytes = 4 + 4 + 1 + 4;

/// Reads the ROS1 wire format (little-endian, arrays and strings after a 4-byte length) of a
/// message in memory, refusing any read past its end.
class WireReader {
 public:
  WireReader(const std::uint8_t* bytes, std::size_t size, const std::string& where)
      : bytes_(bytes), size_(size), where_(where) {}

  template <class T>
  T next(const char* what) {
    need(sizeof(T), what);
    T v;
    std::memcpy(&v, bytes_ + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }

  std::string string(const char* what) {
    const std::uint32_t length = next<std::uint32_t>(what);
    need(length, what);
    std::string s(reinterpret_cast<const char*>(bytes_ + at_), length);
    at_ += length;
    return s;
  }

  /// Fails unless `n` more bytes exist, naming `what` and where it starts.
  void need(std::size_t n, const char* what) const {
    if (n > size_ - at_)
      throw input_error(where_, 0,
                        std::string(what) + " at byte " + std::to_string(at_) + " needs " +
                            std::to_string(n) + " bytes, the message has " + std::to_string(size_ - at_) +
                            " left");
  }

  void skip(std::size_t n, const char* what) {
    need(n, what);
    at_ += n;
  }

  std::size_t at() const { return at_; }
  std::size_t left() const { return size_ - at_; }

 private:
  const std::uint8_t* bytes_;
  std::size_t size_;
  std::string where_;
  std::size_t at_ = 0;
};

}  // namespace

PointCloud2Message parse_point_cloud2_message(const std::uint8_t* bytes, std::size_t size,
                                              const std::string& where) {
  WireReader in(bytes, size, where);
  PointCloud2Message m;
  (void)in.next<std::uint32_t>("header.seq");
  const std::uint32_t sec = in.next<std::uint32_t>("header.stamp");
  const std::uint32_t nsec = in.next<std::uint32_t>("header.stamp");
  m.stamp = static_cast<double>(sec) + 1e-9 * static_cast<double>(nsec);
  m.frame_id = in.string("header.frame_id");
  m.layout.height = in.next<std::uint32_t>("height");
  m.layout.width = in.next<std::uint32_t>("width");
  const std::uint32_t n_fields = in.next<std::uint32_t>("fields");
  if (n_fields > in.left() / kMinSerializedFieldBytes)
    throw input_error(where, 0,
                      "field count " + std::to_string(n_fields) + " at byte " + std::to_string(in.at() - 4) +
                          " is more than the message's " + std::to_string(in.left()) + " bytes can hold");
  m.layout.fields.reserve(n_fields);
  for (std::uint32_t i = 0; i < n_fields; ++i) {
    PointField2 f;
    f.name = in.string("field name");
    f.offset = in.next<std::uint32_t>("field offset");
    f.datatype = in.next<std::uint8_t>("field datatype");
    f.count = in.next<std::uint32_t>("field count");
    m.layout.fields.push_back(std::move(f));
  }
  m.layout.is_bigendian = in.next<std::uint8_t>("is_bigendian") != 0;
  m.layout.point_step = in.next<std::uint32_t>("point_step");
  m.layout.row_step = in.next<std::uint32_t>("row_step");
  m.data_size = in.next<std::uint32_t>("data");
  m.data_offset = in.at();
  in.skip(m.data_size, "data");
  (void)in.next<std::uint8_t>("is_dense");
  return m;
}

}  // namespace tsgraphs::io
