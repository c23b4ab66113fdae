// A run folder's timings.csv read: every column the writer writes, each value checked.
#include "tsgraphs/io/run_folder.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <utility>
#include <vector>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/io/run_folder_internal.hpp"

namespace tsgraphs::io {

using namespace run_folder_internal;

namespace {

// The most points one scan can hold (a 128-beam sensor gives a few million): bounds the ground
// counts of timings.csv.
constexpr long kMaxScanPoints = 1'000'000'000;

// The fields of one CSV line; a field in double quotes may hold commas and doubled quotes.
std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> fields(1);
  bool in_quotes = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (in_quotes) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        in_quotes = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      in_quotes = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  if (in_quotes) throw FieldError("unterminated quoted field");
  return fields;
}

template <class T>
bool parse_whole(const std::string& field, T* v) {
  const char* end = field.data() + field.size();
  const auto r = std::from_chars(field.data(), end, *v);
  return r.ec == std::errc() && r.ptr == end;
}

// timings.csv's columns, in kTimingsHeader's order.
enum TimingColumn {
  kIndex = 1,
  kStamp,
  kKeyframe,
  kNumPoints,
  kPrefilter,
  kWalls,
  kLoop,
  kFrontend,
  kSeconds,
  kFull,
  kVariables,
  kFactors,
  kIterations,
  kReason,
  kGroundMs,
  kGroundNodes,
  kTp,
  kFp,
  kFn,
  kRoomsMs
};

/// Where the header puts each column.
struct TimingsHeader {
  std::vector<std::size_t> col;    ///< of each of kTimingsHeader's names
  std::size_t active_col = 0;      ///< of kActiveKeyframes; past the header's end when it has none
  std::vector<std::string> names;  ///< kTimingsHeader's names
};

/// The header line (line 1): it starts with 'kind', and every column the writer writes must be there.
TimingsHeader read_timings_header(const std::string& path, const std::string& line) {
  std::vector<std::string> header;
  try {
    header = split_csv(line);
  } catch (const FieldError& e) {
    throw input_error(path, 1, e.what());
  }
  if (header[0] != "kind") throw input_error(path, 1, "header must start with 'kind'");
  TimingsHeader h;
  for (const std::string& name : split_csv(kTimingsHeader)) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) throw input_error(path, 1, "header has no column '" + name + "'");
    h.col.push_back(static_cast<std::size_t>(it - header.begin()));
  }
  const auto active_at = std::find(header.begin(), header.end(), kActiveKeyframes);
  h.active_col =
      active_at == header.end() ? header.size() : static_cast<std::size_t>(active_at - header.begin());
  h.names = split_csv(kTimingsHeader);
  return h;
}

/// One row's fields by column, each parsed whole or a FieldError naming the column and the row's kind.
class TimingRow {
 public:
  TimingRow(const std::string& line, const TimingsHeader& h) : cols_(split_csv(line)), h_(h) {}
  const std::string& kind() const { return cols_[0]; }
  const std::string& field(TimingColumn c) const {
    static const std::string kNone;
    return h_.col[c] < cols_.size() ? cols_[h_.col[c]] : kNone;
  }
  double real(TimingColumn c) const {
    double v = 0.0;
    if (!parse_whole(field(c), &v) || !std::isfinite(v)) throw bad(c);
    return v;
  }
  template <class T>
  void whole(TimingColumn c, T* v) const {
    if (!parse_whole(field(c), v)) throw bad(c);
  }
  /// The active_keyframes column, when the file has it (it came later).
  template <class T>
  void active_keyframes(T* v) const {
    if (h_.active_col < cols_.size() && !parse_whole(cols_[h_.active_col], v))
      throw FieldError(std::string("malformed ") + kActiveKeyframes + " in an optimization row");
  }
  const std::string& name(TimingColumn c) const { return h_.names[c]; }

 private:
  FieldError bad(TimingColumn c) const {
    return FieldError("malformed " + h_.names[c] +
                      (kind() == "scan" ? " in a scan row" : " in an optimization row"));
  }
  std::vector<std::string> cols_;
  const TimingsHeader& h_;
};

ScanTiming scan_timing(const TimingRow& row) {
  ScanTiming s;
  row.whole(kIndex, &s.index);
  s.stamp = row.real(kStamp);
  row.whole(kKeyframe, &s.keyframe);
  row.whole(kNumPoints, &s.num_points);
  s.prefilter_ms = row.real(kPrefilter);
  s.walls_ms = row.real(kWalls);
  s.loop_ms = row.real(kLoop);
  s.frontend_ms = row.real(kFrontend);
  s.warning = row.field(kReason);
  s.ground_ms = row.real(kGroundMs);
  row.whole(kGroundNodes, &s.ground_nodes);
  row.whole(kTp, &s.ground_tp);
  row.whole(kFp, &s.ground_fp);
  row.whole(kFn, &s.ground_fn);
  // eval sums these over the scans: a corrupt count must not overflow the sum.
  for (const auto& [c, v] : {std::pair{kTp, s.ground_tp}, {kFp, s.ground_fp}, {kFn, s.ground_fn}}) {
    if (v < -1 || v > kMaxScanPoints)
      throw FieldError(row.name(c) + " in a scan row must be -1 (no labels) or a count of a scan's points");
  }
  s.rooms_ms = row.real(kRoomsMs);
  return s;
}

OptimizationTiming optimization_timing(const TimingRow& row) {
  OptimizationTiming o;
  row.whole(kIndex, &o.index);
  o.stamp = row.real(kStamp);
  row.whole(kKeyframe, &o.keyframe);
  o.seconds = row.real(kSeconds);
  int full = 0;
  row.whole(kFull, &full);
  if (full != 0 && full != 1) throw FieldError("full must be 0 or 1");
  o.full = full == 1;
  row.whole(kVariables, &o.n_variables);
  row.whole(kFactors, &o.n_factors);
  row.whole(kIterations, &o.iterations);
  o.reason = row.field(kReason);
  row.active_keyframes(&o.active_keyframes);
  return o;
}

}  // namespace

Timings read_timings(const std::string& path) {
  std::istringstream in(read_text(path));
  std::string line;
  if (!std::getline(in, line)) throw input_error(path, 1, "empty: expected the header line");
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const TimingsHeader header = read_timings_header(path, line);
  Timings t;
  int line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    try {
      const TimingRow row(line, header);
      if (row.kind() == "scan") {
        t.scans.push_back(scan_timing(row));
      } else if (row.kind() == "optimization") {
        t.optimizations.push_back(optimization_timing(row));
      } else {
        throw FieldError("expected a scan or optimization row, got '" + row.kind() + "'");
      }
    } catch (const FieldError& e) {
      throw input_error(path, line_no, e.what());
    }
  }
  return t;
}

}  // namespace tsgraphs::io
