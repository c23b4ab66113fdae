#include "tsgraphs/io/rosbag2.hpp"

#include <sqlite3.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <mutex>
#include <set>
#include <tuple>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/core/printable.hpp"
#include "tsgraphs/io/compression.hpp"
#include "tsgraphs/io/point_cloud2.hpp"
#include "tsgraphs/io/ros2_messages.hpp"
#include "tsgraphs/io/tum.hpp"

namespace tsgraphs::io {
namespace {

namespace fs = std::filesystem;

constexpr const char* kTfStaticTopic = "/tf_static";
constexpr const char* kMetadataFile = "metadata.yaml";
constexpr char kSqliteMagic[] = "SQLite format 3";  // and a NUL: the first 16 bytes of every SQLite file
constexpr char kMcapMagic[] = "\x89MCAP0\r\n";
// A message decompressed (compression_mode MESSAGE) at most this large, as MCAP chunks: a
// larger one is corrupt, and would allocate what the file does not hold.
constexpr std::uint64_t kMaxMessageBytes = std::uint64_t{1} << 30;

/// A topic as a storage records it.
struct Topic {
  std::string name, type, format;
  std::string definition;  ///< ros2msg text when the storage keeps one
  std::uint64_t count = 0;
};

/// The receive times of a file's first and last messages (ns).
struct TimeSpan {
  std::uint64_t first = 0, last = 0;
};

/// A message's place: its file, and its row (SQLite) or record (MCAP) there.
struct Located {
  std::size_t file = 0;
  std::uint64_t time = 0;  ///< ns
  std::int64_t row = 0;
  mcap::MessageRef ref;
};

class Storage {
 public:
  virtual ~Storage() = default;
  virtual std::vector<Topic> topics() const = 0;
  /// The messages of `topic`, by receive time.
  virtual std::vector<Located> messages(const std::string& topic, std::size_t file) const = 0;
  virtual std::string read(const Located& m) const = 0;
  /// When its first and last messages were received; none for a file without one.
  virtual std::optional<TimeSpan> time_span() const = 0;
  virtual std::vector<std::string> warnings() const { return {}; }
};

std::string head_of(const std::string& path, std::size_t n) {
  std::ifstream in(path, std::ios::binary);
  std::string s(n, '\0');
  in.read(s.data(), static_cast<std::streamsize>(n));
  s.resize(static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  return s;
}

bool is_sqlite(const std::string& path) {
  return head_of(path, sizeof kSqliteMagic) == std::string(kSqliteMagic, sizeof kSqliteMagic);
}
bool is_mcap(const std::string& path) { return head_of(path, 8) == std::string(kMcapMagic, 8); }

/// rosbag2's SQLite storage: tables topics (id, name, type, serialization_format, ...) and
/// messages (id, topic_id, timestamp, data); message_definitions where rosbag2 (Iron on) keeps them.
class SqliteStorage : public Storage {
 public:
  /// The file at `path`, named `shown` in errors.
  SqliteStorage(const std::string& path, const std::string& shown) : path_(shown) {
    if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READONLY | SQLITE_OPEN_FULLMUTEX, nullptr) !=
        SQLITE_OK) {
      const std::string why = db_ ? sqlite3_errmsg(db_) : "out of memory";
      sqlite3_close(db_);
      throw input_error(shown, 0, "cannot open the SQLite file: " + why);
    }
    try {
      for (const char* table : {"topics", "messages"}) {
        if (!has_table(table))
          throw input_error(shown, 0, std::string("not a rosbag2 SQLite file: no table '") + table + "'");
      }
    } catch (...) {  // no destructor runs for an object whose constructor throws (LeakSanitizer found it)
      sqlite3_close(db_);
      throw;
    }
  }
  ~SqliteStorage() override { sqlite3_close(db_); }

  std::vector<Topic> topics() const override {
    std::map<std::string, std::string> definitions;
    if (has_table("message_definitions")) {
      query("SELECT topic_type, encoding, encoded_message_definition FROM message_definitions", {},
            [&](sqlite3_stmt* s) {
              if (text(s, 1) == "ros2msg") definitions[text(s, 0)] = text(s, 2);
            });
    }
    std::map<std::int64_t, std::uint64_t> counts;
    query("SELECT topic_id, COUNT(*) FROM messages GROUP BY topic_id", {}, [&](sqlite3_stmt* s) {
      counts[sqlite3_column_int64(s, 0)] = static_cast<std::uint64_t>(sqlite3_column_int64(s, 1));
    });
    std::vector<Topic> out;
    query("SELECT id, name, type, serialization_format FROM topics ORDER BY id", {}, [&](sqlite3_stmt* s) {
      Topic t{text(s, 1), text(s, 2), text(s, 3), "", counts[sqlite3_column_int64(s, 0)]};
      if (const auto it = definitions.find(t.type); it != definitions.end()) t.definition = it->second;
      out.push_back(t);
    });
    return out;
  }

  std::vector<Located> messages(const std::string& topic, std::size_t file) const override {
    std::vector<Located> out;
    query(
        "SELECT m.id, m.timestamp FROM messages m JOIN topics t ON m.topic_id = t.id WHERE t.name = ?1 "
        "ORDER BY m.timestamp, m.id",
        {topic}, [&](sqlite3_stmt* s) {
          Located m;
          m.file = file;
          m.row = sqlite3_column_int64(s, 0);
          m.time = static_cast<std::uint64_t>(sqlite3_column_int64(s, 1));
          out.push_back(m);
        });
    return out;
  }

  std::string read(const Located& m) const override {
    std::string data;
    bool found = false;
    query("SELECT data FROM messages WHERE id = " + std::to_string(m.row), {}, [&](sqlite3_stmt* s) {
      const auto* blob = static_cast<const char*>(sqlite3_column_blob(s, 0));
      data.assign(blob ? blob : "", static_cast<std::size_t>(sqlite3_column_bytes(s, 0)));
      found = true;
    });
    if (!found) throw input_error(path_, 0, "message row " + std::to_string(m.row) + " is gone");
    return data;
  }

  std::optional<TimeSpan> time_span() const override {
    std::optional<TimeSpan> span;  // rosbag2's timestamp index makes this two lookups
    query("SELECT MIN(timestamp), MAX(timestamp) FROM messages", {}, [&](sqlite3_stmt* s) {
      if (sqlite3_column_type(s, 0) == SQLITE_NULL) return;
      span = TimeSpan{static_cast<std::uint64_t>(sqlite3_column_int64(s, 0)),
                      static_cast<std::uint64_t>(sqlite3_column_int64(s, 1))};
    });
    return span;
  }

 private:
  static std::string text(sqlite3_stmt* s, int column) {
    const auto* t = reinterpret_cast<const char*>(sqlite3_column_text(s, column));
    return t ? std::string(t, static_cast<std::size_t>(sqlite3_column_bytes(s, column))) : "";
  }
  bool has_table(const std::string& name) const {
    bool found = false;
    query("SELECT name FROM sqlite_master WHERE type = 'table' AND name = ?1", {name},
          [&](sqlite3_stmt*) { found = true; });
    return found;
  }
  /// Runs `sql` with text parameters, calling `row` for each result row; SQLite's errors (a
  /// corrupt file, a missing column) are InputErrors naming the file.
  template <class Row>
  void query(const std::string& sql, const std::vector<std::string>& params, Row&& row) const {
    const std::lock_guard<std::mutex> lock(mutex_);
    sqlite3_stmt* s = nullptr;
    if (sqlite3_prepare_v2(db_, sql.c_str(), -1, &s, nullptr) != SQLITE_OK) {
      throw input_error(path_, 0, std::string("SQLite: ") + sqlite3_errmsg(db_));
    }
    for (std::size_t i = 0; i < params.size(); ++i) {
      sqlite3_bind_text(s, static_cast<int>(i + 1), params[i].c_str(), -1, SQLITE_TRANSIENT);
    }
    int rc;
    while ((rc = sqlite3_step(s)) == SQLITE_ROW) {
      try {
        row(s);
      } catch (...) {
        sqlite3_finalize(s);
        throw;
      }
    }
    sqlite3_finalize(s);
    if (rc != SQLITE_DONE) throw input_error(path_, 0, std::string("SQLite: ") + sqlite3_errmsg(db_));
  }

  std::string path_;
  sqlite3* db_ = nullptr;
  mutable std::mutex mutex_;
};

/// rosbag2's MCAP storage: a channel per topic (message encoding cdr), its schema the type's
/// name and ros2msg definition.
class McapStorage : public Storage {
 public:
  McapStorage(const std::string& path, const std::string& shown) : reader_(path, shown) {}
  std::vector<Topic> topics() const override {
    std::map<std::string, Topic> by_name;
    std::map<std::uint16_t, std::uint64_t> counts;
    for (const mcap::MessageRef& m : reader_.messages()) ++counts[m.channel_id];
    for (const auto& [id, c] : reader_.channels()) {
      Topic& t = by_name[c.topic];
      t.name = c.topic;
      t.format = c.message_encoding;
      if (const auto s = reader_.schemas().find(c.schema_id); s != reader_.schemas().end()) {
        t.type = s->second.name;
        if (s->second.encoding == "ros2msg") t.definition = s->second.data;
      }
      t.count += counts[id];
    }
    std::vector<Topic> out;
    for (auto& [name, t] : by_name) out.push_back(std::move(t));
    return out;
  }
  std::vector<Located> messages(const std::string& topic, std::size_t file) const override {
    std::vector<Located> out;
    for (const mcap::MessageRef& m : reader_.messages()) {
      if (reader_.channels().at(m.channel_id).topic != topic) continue;
      Located l;
      l.file = file;
      l.time = m.log_time;
      l.ref = m;
      out.push_back(l);
    }
    return out;
  }
  std::string read(const Located& m) const override { return reader_.read(m.ref).data; }
  std::optional<TimeSpan> time_span() const override {
    std::optional<TimeSpan> span;  // the message list is in memory once the file is open
    for (const mcap::MessageRef& m : reader_.messages()) {
      span = span ? TimeSpan{std::min(span->first, m.log_time), std::max(span->last, m.log_time)}
                  : TimeSpan{m.log_time, m.log_time};
    }
    return span;
  }
  std::vector<std::string> warnings() const override { return reader_.warnings(); }

 private:
  mcap::Reader reader_;
};

/// Messages rosbag2 compressed one by one (compression_mode MESSAGE), decompressed as read.
class ZstdMessages : public Storage {
 public:
  ZstdMessages(std::unique_ptr<Storage> inner, std::string path)
      : inner_(std::move(inner)), path_(std::move(path)) {}
  std::vector<Topic> topics() const override { return inner_->topics(); }
  std::vector<Located> messages(const std::string& topic, std::size_t file) const override {
    return inner_->messages(topic, file);
  }
  std::string read(const Located& m) const override {
    const std::string packed = inner_->read(m);
    return decompress_zstd(packed.data(), packed.size(), kMaxMessageBytes, path_,
                           "the message received at " + std::to_string(m.time) + " ns");
  }
  std::optional<TimeSpan> time_span() const override { return inner_->time_span(); }
  std::vector<std::string> warnings() const override { return inner_->warnings(); }

 private:
  std::unique_ptr<Storage> inner_;
  std::string path_;
};

/// The storage in the file at `path` (SQLite or MCAP, by content), named `shown` in errors.
std::unique_ptr<Storage> open_storage(const std::string& path, const std::string& shown) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw input_error(shown, 0, "no such file");
  if (is_sqlite(path)) return std::make_unique<SqliteStorage>(path, shown);
  if (is_mcap(path)) return std::make_unique<McapStorage>(path, shown);
  throw input_error(shown, 0, "neither an SQLite (.db3) nor an MCAP file");
}

/// A storage file rosbag2 compressed whole (compression_mode FILE): decompressed to a temporary
/// file that is unlinked as soon as the storage holds it open, so that nothing is left behind
/// however the run ends (the open descriptor keeps it readable).
std::unique_ptr<Storage> open_compressed_storage(const std::string& path) {
  static std::atomic<unsigned> count{0};
  const fs::path tmp =
      fs::temp_directory_path() / ("tsgraphs-" + std::to_string(::getpid()) + "-" + std::to_string(count++) +
                                   "-" + fs::path(path).stem().string());
  struct Unlink {
    fs::path path;
    ~Unlink() {
      std::error_code ec;
      fs::remove(path, ec);
    }
  } unlink{tmp};
  decompress_zstd_file(path, tmp.string());
  return open_storage(tmp.string(), path);
}

/// rosbag2's own compression of a recording, as metadata.yaml states it (file:line naming it).
Rosbag2Compression compression_of(const YAML::Node& info, const std::string& metadata) {
  const auto scalar = [&](const char* key) {
    const YAML::Node n = info[key];
    return std::make_pair(n && n.IsScalar() ? n.as<std::string>() : std::string(), n ? n.Mark().line + 1 : 0);
  };
  const auto [written, mode_line] = scalar("compression_mode");
  std::string mode = written;  // rosbag2 writes FILE and MESSAGE; its reader takes any case
  std::transform(mode.begin(), mode.end(), mode.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  Rosbag2Compression out;
  if (mode.empty() || mode == "none") return Rosbag2Compression::none;
  if (mode == "file") {
    out = Rosbag2Compression::file;
  } else if (mode == "message") {
    out = Rosbag2Compression::message;
  } else {
    throw input_error(metadata, mode_line,
                      "compression_mode " + printable(written) + ": expected FILE, MESSAGE or none");
  }
  if (const auto [format, line] = scalar("compression_format"); format != "zstd") {
    throw input_error(
        metadata, line,
        "compression_format '" + printable(format) + "': only zstd, rosbag2's own compressor, is read");
  }
  return out;
}

/// metadata.yaml's rosbag2_bagfile_information, a map, or an InputError naming the file.
YAML::Node bagfile_information(const std::string& metadata) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(metadata);
  } catch (const YAML::Exception& e) {  // its message quotes the byte it stumbled on, raw
    throw input_error(metadata, e.mark.line + 1, "not YAML: " + printable(e.msg, e.msg.size()));
  }
  const YAML::Node info = root.IsMap() ? root["rosbag2_bagfile_information"] : YAML::Node();
  if (!info || !info.IsMap() || !info["relative_file_paths"] || !info["relative_file_paths"].IsSequence()) {
    throw input_error(metadata, 0, "no rosbag2_bagfile_information.relative_file_paths");
  }
  return info;
}

/// The file `entry` of relative_file_paths names in `folder`: a file there, listed once. The same
/// file under another spelling (./a.db3 and a.db3, a link to it) is a repeat too: read twice, its
/// scans would come twice and time would go back. `listed` holds the files so far, by their
/// canonical path, with the line that listed each.
std::string listed_file(const YAML::Node& entry, const std::string& folder, const std::string& metadata,
                        std::map<fs::path, std::pair<std::string, int>>& listed) {
  const int line = entry.Mark().line + 1;
  if (!entry.IsScalar())
    throw input_error(metadata, line, "relative_file_paths: an entry that is not a file name");
  const std::string name = entry.Scalar();
  // rosbag2 names files relative to the bag folder; an absolute name or one climbing out of it
  // would read a file elsewhere.
  const fs::path home = fs::absolute(folder).lexically_normal();
  const fs::path relative = (home / name).lexically_normal().lexically_relative(home);
  if (fs::path(name).is_absolute())
    throw input_error(metadata, line,
                      "lists " + printable(name) + ", an absolute path: files are named from the bag folder");
  if (relative.empty() || *relative.begin() == "..")
    throw input_error(metadata, line, "lists " + printable(name) + ", which is not inside the bag folder");
  const std::string file = (fs::path(folder) / name).string();
  std::error_code ec;
  if (!fs::is_regular_file(file, ec))
    throw input_error(metadata, line, "lists " + printable(name) + ", which is not in the folder");
  const fs::path canonical = fs::canonical(file, ec);
  if (ec)
    throw input_error(metadata, line, "lists " + printable(name) + ", which cannot be read: " + ec.message());
  const auto [first, fresh] = listed.emplace(canonical, std::make_pair(name, line));
  if (!fresh) {
    throw input_error(metadata, line,
                      "lists " + printable(name) + " again (as " + printable(first->second.first) +
                          " on line " + std::to_string(first->second.second) + "): each file is read once");
  }
  return file;
}

/// A time in ns as seconds to the nanosecond, for messages.
std::string seconds(std::uint64_t ns) {
  constexpr std::uint64_t kNsPerSecond = 1000000000;
  char text[48];
  std::snprintf(text, sizeof text, "%llu.%09llu s", static_cast<unsigned long long>(ns / kNsPerSecond),
                static_cast<unsigned long long>(ns % kNsPerSecond));
  return text;
}

/// rosbag2 starts a split's next file once the last is full, so each file's messages follow the
/// previous file's. One that starts before the last message of the file before it is a file
/// listed again under another name (a copy): its messages would be read twice, time going back.
/// Equal times pass: two topics' messages of one instant may fall either side of a split.
void check_follows(const std::string& metadata, int line, const std::string& file, const TimeSpan& span,
                   const std::string& previous_file, const TimeSpan& previous) {
  if (span.first >= previous.last) return;
  throw input_error(metadata, line,
                    printable(file) + ": its first message (t " + seconds(span.first) +
                        ") is before the last of " + printable(previous_file) + " (t " +
                        seconds(previous.last) + "): a file repeated?");
}

/// The span metadata.yaml's `files` section gives a file (rosbag2 from Humble on writes each
/// file's path, starting_time and duration there), by the name it lists, with the entry's line.
/// An entry without readable times gives none: that file is checked once it is read.
std::map<std::string, std::pair<TimeSpan, int>> listed_spans(const YAML::Node& info) {
  std::map<std::string, std::pair<TimeSpan, int>> out;
  const YAML::Node files = info["files"];
  if (!files || !files.IsSequence()) return out;
  for (const YAML::Node& f : files) {
    try {
      const std::string path = f["path"].as<std::string>();
      const auto start = f["starting_time"]["nanoseconds_since_epoch"].as<std::uint64_t>();
      const auto duration = f["duration"]["nanoseconds"].as<std::uint64_t>();
      if (duration > std::numeric_limits<std::uint64_t>::max() - start) continue;  // no time of a message
      out.emplace(path, std::make_pair(TimeSpan{start, start + duration}, f.Mark().line + 1));
    } catch (const YAML::Exception&) {
      continue;  // not a file's times as rosbag2 writes them: read the file instead
    }
  }
  return out;
}

/// Split files in time order, as far as metadata.yaml gives their times: a repeat is refused
/// before any file is opened (a FILE-compressed one decompressed).
void check_listed_order(const YAML::Node& info, const Rosbag2Metadata& listed, const std::string& metadata) {
  const std::map<std::string, std::pair<TimeSpan, int>> spans = listed_spans(info);
  for (std::size_t i = 1; i < listed.names.size(); ++i) {
    const auto previous = spans.find(listed.names[i - 1]), span = spans.find(listed.names[i]);
    if (previous == spans.end() || span == spans.end()) continue;
    check_follows(metadata, span->second.second, listed.names[i], span->second.first, listed.names[i - 1],
                  previous->second.first);
  }
}

}  // namespace

Rosbag2Metadata read_rosbag2_metadata(const std::string& folder) {
  const std::string metadata = (fs::path(folder) / kMetadataFile).string();
  std::error_code ec;
  if (!fs::is_regular_file(metadata, ec))
    throw input_error(folder, 0, "a folder without metadata.yaml: not a rosbag2 bag");
  const YAML::Node info = bagfile_information(metadata);
  Rosbag2Metadata out;
  out.compression = compression_of(info, metadata);
  std::map<fs::path, std::pair<std::string, int>> listed;
  for (const YAML::Node& entry : info["relative_file_paths"]) {
    out.files.push_back(listed_file(entry, folder, metadata, listed));
    out.names.push_back(entry.Scalar());
  }
  if (out.files.empty()) throw input_error(metadata, 0, "lists no files");
  check_listed_order(info, out, metadata);
  return out;
}

namespace {

/// The storages of a recording: a folder's files in metadata.yaml's order, or the one file.
std::vector<std::unique_ptr<Storage>> open_recording(const std::string& path) {
  std::vector<std::unique_ptr<Storage>> out;
  std::error_code ec;
  if (!fs::is_directory(path, ec)) {
    out.push_back(open_storage(path, path));
    return out;
  }
  const Rosbag2Metadata metadata = read_rosbag2_metadata(path);
  std::optional<TimeSpan> previous;  // the last file's with a message
  std::string previous_name;
  for (std::size_t i = 0; i < metadata.files.size(); ++i) {
    const std::string& file = metadata.files[i];
    if (metadata.compression == Rosbag2Compression::file) {
      out.push_back(open_compressed_storage(file));
    } else if (metadata.compression == Rosbag2Compression::message) {
      out.push_back(std::make_unique<ZstdMessages>(open_storage(file, file), file));
    } else {
      out.push_back(open_storage(file, file));
    }
    // The files' own times: metadata.yaml may give none, or not the file's.
    const std::optional<TimeSpan> span = out.back()->time_span();
    if (!span) continue;
    if (previous)
      check_follows((fs::path(path) / kMetadataFile).string(), 0, metadata.names[i], *span, previous_name,
                    *previous);
    previous = span;
    previous_name = metadata.names[i];
  }
  return out;
}

/// Topics of every file, merged by name; a topic of two types is an error.
std::map<std::string, Topic> topics_of(const std::vector<std::unique_ptr<Storage>>& storages,
                                       const std::string& path) {
  std::map<std::string, Topic> out;
  for (const auto& s : storages) {
    for (const Topic& t : s->topics()) {
      auto [it, fresh] = out.emplace(t.name, t);
      if (fresh) continue;
      if (it->second.type != t.type)
        throw input_error(path, 0,
                          t.name + " is " + it->second.type + " in one file, " + t.type + " in another");
      it->second.count += t.count;
    }
  }
  return out;
}

std::vector<Located> messages_of(const std::vector<std::unique_ptr<Storage>>& storages,
                                 const std::string& topic) {
  std::vector<Located> out;
  for (std::size_t i = 0; i < storages.size(); ++i) {
    const std::vector<Located> m = storages[i]->messages(topic, i);
    out.insert(out.end(), m.begin(), m.end());
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const Located& a, const Located& b) { return a.time < b.time; });
  return out;
}

}  // namespace

bool is_rosbag2(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) return fs::is_regular_file(fs::path(path) / kMetadataFile, ec);
  return fs::is_regular_file(path, ec) && (is_sqlite(path) || is_mcap(path));
}

struct Rosbag2Sequence::Impl {
  std::vector<std::unique_ptr<Storage>> storages;
  std::vector<Located> clouds;  ///< one per kept scan
  std::string topic;
};

Rosbag2Sequence::Rosbag2Sequence(const BagOptions& options)
    : RecordedSequence(options.bag), impl_(std::make_unique<Impl>()) {
  const std::string& path = options.bag;
  if (options.points_topic.empty())
    throw input_error(path, 0, "no points topic given (--points-topic; see bag-info)");
  impl_->storages = open_recording(path);
  for (const auto& s : impl_->storages) {
    for (const std::string& w : s->warnings()) warnings_.push_back(w);
  }
  const std::map<std::string, Topic> topics = topics_of(impl_->storages, path);
  const auto require = [&](const std::string& topic, const std::vector<const char*>& wanted) -> const Topic& {
    const auto it = topics.find(topic);
    if (it == topics.end()) {
      std::string list;
      for (const auto& [t, info] : topics) list += (list.empty() ? "" : ", ") + t;
      throw input_error(path, 0, "no topic " + topic + " (topics: " + list + ")");
    }
    const Topic& t = it->second;
    if (std::find(wanted.begin(), wanted.end(), t.type) == wanted.end()) {
      std::string names;
      for (const char* w : wanted) names += std::string(names.empty() ? "" : " or ") + w;
      throw input_error(path, 0, topic + " is " + t.type + ", expected " + names);
    }
    if (t.format != "cdr")
      throw input_error(path, 0, topic + " is serialized as '" + t.format + "', expected cdr");
    if (const std::string why = ros2::definition_mismatch(t.type, t.definition); !why.empty()) {
      throw input_error(path, 0, topic + " (" + t.type + "): " + why);
    }
    return t;
  };
  impl_->topic = options.points_topic;
  require(options.points_topic, {ros2::kPointCloud2});
  const auto where = [&](const std::string& topic, std::size_t i) {
    return path + ": " + topic + ", message " + std::to_string(i);
  };
  const auto read = [&](const Located& m) { return impl_->storages[m.file]->read(m); };

  bool is_odometry = false;
  std::vector<Located> odom_messages;
  if (!options.odom_topic.empty()) {
    is_odometry = require(options.odom_topic, {ros2::kOdometry, ros2::kPoseStamped}).type == ros2::kOdometry;
    odom_messages = messages_of(impl_->storages, options.odom_topic);
  }
  const std::vector<Located> clouds = messages_of(impl_->storages, options.points_topic);
  if (clouds.empty()) throw input_error(path, 0, "no messages on " + options.points_topic);

  // The odometry and the clouds' stamps read in one pass in file order, so that an MCAP chunk
  // holding both is decompressed once.
  struct Read {
    const Located* m;
    bool cloud;
    std::size_t i;  ///< index in its topic, by time
  };
  std::vector<Read> reads;
  for (std::size_t i = 0; i < odom_messages.size(); ++i) reads.push_back({&odom_messages[i], false, i});
  for (std::size_t i = 0; i < clouds.size(); ++i) reads.push_back({&clouds[i], true, i});
  const auto position = [](const Located& m) {
    const bool chunked = m.ref.chunk != mcap::MessageRef::kNoChunk;
    return std::make_tuple(m.file, chunked ? m.ref.chunk : m.ref.offset, chunked ? m.ref.offset : 0, m.row);
  };
  std::sort(reads.begin(), reads.end(),
            [&](const Read& a, const Read& b) { return position(*a.m) < position(*b.m); });
  std::vector<StampedBase> odom(odom_messages.size());
  std::vector<double> stamps(clouds.size());
  std::string cloud_frame;  // the first cloud's
  for (const Read& r : reads) {
    const std::string cdr = read(*r.m);
    if (r.cloud) {
      const PointCloud2Message c = ros2::parse_point_cloud2(cdr, where(options.points_topic, r.i));
      stamps[r.i] = c.stamp;
      if (r.i == 0) cloud_frame = c.frame_id;
    } else {
      const ros2::StampedPoseMessage p = is_odometry
                                             ? ros2::parse_odometry(cdr, where(options.odom_topic, r.i))
                                             : ros2::parse_pose_stamped(cdr, where(options.odom_topic, r.i));
      odom[r.i] = {p.stamp, p.pose};
    }
  }
  if (options.odom_topic.empty() && !options.odom_tum.empty()) {
    for (const StampedPose& p : read_tum(options.odom_tum)) odom.push_back({p.t, p.pose});
  }
  const bool has_odometry = !options.odom_topic.empty() || !options.odom_tum.empty();
  if (has_odometry && odom.empty())
    throw input_error(
        path, 0,
        "no odometry messages on " + (options.odom_topic.empty() ? options.odom_tum : options.odom_topic));

  if (options.sensor_to_base) {
    sensor_to_base_ = *options.sensor_to_base;
    sensor_to_base_known_ = true;
  } else if (topics.count(kTfStaticTopic)) {
    require(kTfStaticTopic, {ros2::kTfMessage});
    std::size_t i = 0;
    for (const Located& m : messages_of(impl_->storages, kTfStaticTopic)) {
      for (const ros2::TransformMessage& t : ros2::parse_tf_message(read(m), where(kTfStaticTopic, i++))) {
        if (t.child != cloud_frame) continue;
        sensor_to_base_ = t.transform;
        sensor_to_base_known_ = true;
      }
    }
  }

  ScanPlacement placed = place_scans(stamps, std::move(odom), has_odometry, sensor_to_base_);
  for (const std::size_t i : placed.kept) impl_->clouds.push_back(clouds[i]);
  info_.times = std::move(placed.times);
  info_.odometry = std::move(placed.odometry);
  dropped_ = placed.dropped;
  if (info_.times.empty())
    throw input_error(path, 0,
                      "no scan on " + options.points_topic + " lies within the odometry's time span");
}

Rosbag2Sequence::~Rosbag2Sequence() = default;

PointCloud Rosbag2Sequence::scan(std::size_t index) const {
  const Located& m = impl_->clouds.at(index);
  const std::string where = name_ + ": " + impl_->topic + ", scan " + std::to_string(index);
  const std::string cdr = impl_->storages[m.file]->read(m);
  const PointCloud2Message msg = ros2::parse_point_cloud2(cdr, where);
  return decode_point_cloud2(msg.layout, reinterpret_cast<const std::uint8_t*>(cdr.data()) + msg.data_offset,
                             msg.data_size, where);
}

std::string rosbag2_info(const std::string& path) {
  const auto storages = open_recording(path);
  std::string out =
      path + ": " + std::to_string(storages.size()) + " file" + (storages.size() == 1 ? "" : "s") + "\n";
  for (const auto& [name, t] : topics_of(storages, path)) {
    const std::vector<Located> m = messages_of(storages, name);
    const double span = m.size() >= 2 ? 1e-9 * static_cast<double>(m.back().time - m.front().time) : 0.0;
    char line[512];
    std::snprintf(line, sizeof line, "  %-24s %-32s %8zu msgs", name.c_str(), t.type.c_str(), m.size());
    out += line;
    if (span > 0) {
      std::snprintf(line, sizeof line, "  %8.2f Hz", static_cast<double>(m.size() - 1) / span);
      out += line;
    }
    out += "\n";
  }
  for (const auto& s : storages) {
    for (const std::string& w : s->warnings()) out += "  warning: " + w + "\n";
  }
  return out;
}

// ---- writing -------------------------------------------------------------------------------

namespace {

/// Offered QoS as rosbag2 records it (YAML): reliable; /tf_static transient local, as tf2 publishes it.
std::string qos_profile(bool transient_local) {
  return std::string("- history: 3\n  depth: 0\n  reliability: 1\n  durability: ") +
         (transient_local ? "1" : "2") +
         "\n  deadline:\n    sec: 2147483647\n    nsec: 4294967295\n  lifespan:\n    sec: 2147483647\n"
         "    nsec: 4294967295\n  liveliness: 1\n  liveliness_lease_duration:\n    sec: 2147483647\n"
         "    nsec: 4294967295\n  avoid_ros_namespace_conventions: false";
}

struct TopicToWrite {
  std::string name, type;
  bool transient_local = false;
};

/// One message to write: its topic's index in the list and its CDR.
struct Out {
  std::size_t topic;
  std::uint64_t time;
  std::string cdr;
};

/// What metadata.yaml says of the messages: per topic its count, and the time span.
struct Tally {
  std::vector<std::uint64_t> counts;
  std::uint64_t first = 0, last = 0, total = 0;
  void add(const Out& m) {
    if (counts.size() <= m.topic) counts.resize(m.topic + 1, 0);
    ++counts[m.topic];
    first = total ? std::min(first, m.time) : m.time;
    last = total ? std::max(last, m.time) : m.time;
    ++total;
  }
};

/// rosbag2's BagMetadata (version 5, as Humble writes it) for one file, listed as `file`.
std::string bag_metadata(const std::string& storage_id, const std::string& file,
                         const std::vector<TopicToWrite>& topics, const Tally& tally,
                         Rosbag2Compression compression) {
  YAML::Emitter y;
  const auto duration = [&] {
    y << YAML::BeginMap << YAML::Key << "nanoseconds" << YAML::Value << tally.last - tally.first
      << YAML::EndMap;
  };
  const auto starting = [&] {
    y << YAML::BeginMap << YAML::Key << "nanoseconds_since_epoch" << YAML::Value << tally.first
      << YAML::EndMap;
  };
  y << YAML::BeginMap << YAML::Key << "rosbag2_bagfile_information" << YAML::Value << YAML::BeginMap;
  y << YAML::Key << "version" << YAML::Value << 5;
  y << YAML::Key << "storage_identifier" << YAML::Value << storage_id;
  y << YAML::Key << "duration" << YAML::Value, duration();
  y << YAML::Key << "starting_time" << YAML::Value, starting();
  y << YAML::Key << "message_count" << YAML::Value << tally.total;
  y << YAML::Key << "topics_with_message_count" << YAML::Value << YAML::BeginSeq;
  for (std::size_t i = 0; i < topics.size(); ++i) {
    y << YAML::BeginMap << YAML::Key << "topic_metadata" << YAML::Value << YAML::BeginMap;
    y << YAML::Key << "name" << YAML::Value << topics[i].name;
    y << YAML::Key << "type" << YAML::Value << topics[i].type;
    y << YAML::Key << "serialization_format" << YAML::Value << "cdr";
    y << YAML::Key << "offered_qos_profiles" << YAML::Value << YAML::DoubleQuoted
      << qos_profile(topics[i].transient_local);
    y << YAML::EndMap;
    y << YAML::Key << "message_count" << YAML::Value << (i < tally.counts.size() ? tally.counts[i] : 0);
    y << YAML::EndMap;
  }
  y << YAML::EndSeq;
  const bool compressed = compression != Rosbag2Compression::none;
  y << YAML::Key << "compression_format" << YAML::Value << YAML::DoubleQuoted << (compressed ? "zstd" : "");
  y << YAML::Key << "compression_mode" << YAML::Value << YAML::DoubleQuoted
    << (!compressed                               ? ""
        : compression == Rosbag2Compression::file ? "FILE"
                                                  : "MESSAGE");
  y << YAML::Key << "relative_file_paths" << YAML::Value << YAML::BeginSeq << file << YAML::EndSeq;
  y << YAML::Key << "files" << YAML::Value << YAML::BeginSeq << YAML::BeginMap;
  y << YAML::Key << "path" << YAML::Value << file;
  y << YAML::Key << "starting_time" << YAML::Value, starting();
  y << YAML::Key << "duration" << YAML::Value, duration();
  y << YAML::Key << "message_count" << YAML::Value << tally.total;
  y << YAML::EndMap << YAML::EndSeq;
  y << YAML::EndMap << YAML::EndMap;
  return std::string(y.c_str()) + "\n";
}

/// How a bag is laid out: the name metadata.yaml lists its file under, rosbag2's own compression.
struct Layout {
  std::string file;
  Rosbag2Compression compression = Rosbag2Compression::none;
};

/// Every message of `sequence` in write_bag's order: /tf_static, then per scan /points, /odom
/// and /groundtruth; each message's data zstd-compressed in MESSAGE mode.
template <class Sink>
void for_each_message(const ScanSequence& sequence, const Pose3& sensor_to_base,
                      Rosbag2Compression compression, Sink&& write) {
  const auto sink = [&](Out m) {
    if (compression == Rosbag2Compression::message) m.cdr = compress_zstd(m.cdr);
    write(m);
  };
  const SequenceInfo& info = sequence.info();
  const double first = info.times.empty() ? 0.0 : info.times.front();
  const auto stamp_ns = ros2::stamp_nanoseconds;
  sink(Out{2, stamp_ns(first), ros2::encode_tf_message({{first, "base_link", "lidar", sensor_to_base}})});
  const Pose3 base_to_sensor = sensor_to_base.inverse();
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    sink(
        Out{0, stamp_ns(info.times[i]), ros2::encode_point_cloud2(info.times[i], "lidar", sequence.scan(i))});
    sink(Out{1, stamp_ns(info.times[i]),
             ros2::encode_odometry({info.times[i], "odom", "base_link", info.odometry[i] * base_to_sensor})});
    if (i < info.groundtruth.size())
      sink(Out{3, stamp_ns(info.times[i]),
               ros2::encode_pose_stamped({info.times[i], "world", "", info.groundtruth[i]})});
  }
}

/// Returns the bag's metadata (for metadata.yaml); `file` is the name it lists.
std::string write_sqlite(const ScanSequence& sequence, const std::string& tmp, const Layout& layout,
                         const std::vector<TopicToWrite>& topics, const Pose3& sensor_to_base) {
  std::string metadata;
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(tmp.c_str(), &db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) != SQLITE_OK) {
    sqlite3_close(db);
    throw input_error(tmp, 0, "cannot create the SQLite file");
  }
  const auto exec = [&](const std::string& sql) {
    char* error = nullptr;
    if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error) != SQLITE_OK) {
      const std::string why = error ? error : "unknown";
      sqlite3_free(error);
      throw std::runtime_error(tmp + ": SQLite: " + why);
    }
  };
  try {
    exec(
        "PRAGMA journal_mode = OFF; PRAGMA synchronous = OFF; BEGIN;"
        "CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL);"
        "INSERT INTO schema VALUES (3, 'humble');"
        "CREATE TABLE metadata(id INTEGER PRIMARY KEY, metadata_version INTEGER NOT NULL, metadata TEXT NOT "
        "NULL);"
        "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
        "serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);"
        "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp INTEGER NOT "
        "NULL, "
        "data BLOB NOT NULL);"
        "CREATE INDEX timestamp_idx ON messages (timestamp ASC);");
    for (std::size_t i = 0; i < topics.size(); ++i) {
      sqlite3_stmt* s = nullptr;
      sqlite3_prepare_v2(db, "INSERT INTO topics VALUES (?1, ?2, ?3, 'cdr', ?4)", -1, &s, nullptr);
      sqlite3_bind_int64(s, 1, static_cast<sqlite3_int64>(i + 1));
      sqlite3_bind_text(s, 2, topics[i].name.c_str(), -1, SQLITE_TRANSIENT);
      sqlite3_bind_text(s, 3, topics[i].type.c_str(), -1, SQLITE_TRANSIENT);
      sqlite3_bind_text(s, 4, qos_profile(topics[i].transient_local).c_str(), -1, SQLITE_TRANSIENT);
      const int rc = sqlite3_step(s);
      sqlite3_finalize(s);
      if (rc != SQLITE_DONE) throw std::runtime_error(tmp + ": SQLite: " + sqlite3_errmsg(db));
    }
    sqlite3_stmt* insert = nullptr;
    sqlite3_prepare_v2(db, "INSERT INTO messages (topic_id, timestamp, data) VALUES (?1, ?2, ?3)", -1,
                       &insert, nullptr);
    Tally tally;
    try {
      for_each_message(sequence, sensor_to_base, layout.compression, [&](const Out& m) {
        tally.add(m);
        sqlite3_reset(insert);
        sqlite3_bind_int64(insert, 1, static_cast<sqlite3_int64>(m.topic + 1));
        sqlite3_bind_int64(insert, 2, static_cast<sqlite3_int64>(m.time));
        sqlite3_bind_blob(insert, 3, m.cdr.data(), static_cast<int>(m.cdr.size()), SQLITE_TRANSIENT);
        if (sqlite3_step(insert) != SQLITE_DONE)
          throw std::runtime_error(tmp + ": SQLite: " + sqlite3_errmsg(db));
      });
    } catch (...) {
      sqlite3_finalize(insert);
      throw;
    }
    sqlite3_finalize(insert);
    metadata = bag_metadata("sqlite3", layout.file, topics, tally, layout.compression);
    sqlite3_stmt* s = nullptr;
    sqlite3_prepare_v2(db, "INSERT INTO metadata (metadata_version, metadata) VALUES (5, ?1)", -1, &s,
                       nullptr);
    sqlite3_bind_text(s, 1, metadata.c_str(), -1, SQLITE_TRANSIENT);
    const int rc = sqlite3_step(s);
    sqlite3_finalize(s);
    if (rc != SQLITE_DONE) throw std::runtime_error(tmp + ": SQLite: " + sqlite3_errmsg(db));
    exec("COMMIT;");
  } catch (...) {
    sqlite3_close(db);
    throw;
  }
  if (sqlite3_close(db) != SQLITE_OK) throw std::runtime_error(tmp + ": SQLite: cannot close");
  return metadata;
}

std::string write_mcap(const ScanSequence& sequence, const std::string& path, const Layout& layout,
                       const std::vector<TopicToWrite>& topics, mcap::Compression compression,
                       const Pose3& sensor_to_base) {
  mcap::WriterOptions o;
  o.profile = "ros2";
  o.compression = compression;
  mcap::Writer w(path, o);
  std::map<std::string, std::uint16_t> schemas;
  std::vector<std::uint16_t> channels;
  for (const TopicToWrite& t : topics) {
    if (!schemas.count(t.type)) schemas[t.type] = w.add_schema(t.type, "ros2msg", ros2::definition(t.type));
    channels.push_back(w.add_channel(schemas[t.type], t.name, "cdr",
                                     {{"offered_qos_profiles", qos_profile(t.transient_local)}}));
  }
  Tally tally;
  for_each_message(sequence, sensor_to_base, layout.compression, [&](const Out& m) {
    tally.add(m);
    w.write(channels[m.topic], m.time, m.time, m.cdr);
  });
  const std::string metadata = bag_metadata("mcap", layout.file, topics, tally, layout.compression);
  w.add_metadata("rosbag2", {{"serialized_metadata", metadata}, {"ROS_DISTRO", "humble"}});
  w.finish();
  return metadata;
}

}  // namespace

void write_rosbag2(const ScanSequence& sequence, const std::string& path, Rosbag2Storage storage,
                   mcap::Compression compression, const Pose3& sensor_to_base,
                   Rosbag2Compression bag_compression) {
  std::vector<TopicToWrite> topics = {{"/points", ros2::kPointCloud2, false},
                                      {"/odom", ros2::kOdometry, false},
                                      {kTfStaticTopic, ros2::kTfMessage, true}};
  if (!sequence.info().groundtruth.empty()) topics.push_back({"/groundtruth", ros2::kPoseStamped, false});
  const std::string ext = storage == Rosbag2Storage::mcap ? ".mcap" : ".db3";
  const bool folder = fs::path(path).extension() != ext;
  // A folder is made under a temporary name; a single file is written to one.
  const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
  const std::string file =
      folder ? fs::path(path).filename().string() + "_0" + ext : fs::path(path).filename().string();
  const std::string target = folder ? (fs::path(tmp) / file).string() : tmp;
  const bool file_compressed = bag_compression == Rosbag2Compression::file;
  const Layout layout{file_compressed ? file + ".zstd" : file, bag_compression};
  std::error_code ec;
  if (!folder && bag_compression != Rosbag2Compression::none) {
    throw input_error(path, 0,
                      "rosbag2's own compression is for a bag folder, whose metadata.yaml records it: give a "
                      "name without " +
                          ext);
  }
  if (folder && fs::exists(path, ec)) throw input_error(path, 0, "exists: a bag folder is not written over");
  fs::remove_all(tmp, ec);
  try {
    if (folder && !fs::create_directory(tmp, ec))
      throw input_error(path, 0, "cannot make the bag folder: " + ec.message());
    const std::string metadata =
        storage == Rosbag2Storage::mcap
            ? write_mcap(sequence, target, layout, topics, compression, sensor_to_base)
            : write_sqlite(sequence, target, layout, topics, sensor_to_base);
    if (file_compressed) {  // as rosbag2 does once a file is closed: the file replaced by its .zstd
      compress_zstd_file(target, target + ".zstd");
      fs::remove(target);
    }
    if (folder) {
      std::ofstream out(fs::path(tmp) / kMetadataFile);
      out << metadata;
      if (!out) throw std::runtime_error(tmp + ": cannot write metadata.yaml");
    }
  } catch (...) {
    fs::remove_all(tmp, ec);
    throw;
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove_all(tmp, ec);
    throw input_error(path, 0, "cannot rename into place: " + ec.message());
  }
}

}  // namespace tsgraphs::io
