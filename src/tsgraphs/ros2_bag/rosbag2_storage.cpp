// rosbag2's storages read: SQLite and MCAP files, rosbag2's own zstd compression, a recording's files.
#include "tsgraphs/ros2_bag/rosbag2.hpp"

#include <sqlite3.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>

#include "tsgraphs/core/error.hpp"
#include "tsgraphs/mcap/compression.hpp"
#include "tsgraphs/ros2_bag/rosbag2_internal.hpp"

namespace tsgraphs::ros2_bag {

using namespace rosbag2_internal;

namespace {

namespace fs = std::filesystem;

constexpr char kSqliteMagic[] = "SQLite format 3";  // and a NUL: the first 16 bytes of every SQLite file
constexpr char kMcapMagic[] = "\x89MCAP0\r\n";
// A message decompressed (compression_mode MESSAGE) at most this large, as MCAP chunks: a
// larger one is corrupt, and would allocate what the file does not hold.
constexpr std::uint64_t kMaxMessageBytes = std::uint64_t{1} << 30;

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
    return mcap::decompress_zstd(packed.data(), packed.size(), kMaxMessageBytes, path_,
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
  mcap::decompress_zstd_file(path, tmp.string());
  return open_storage(tmp.string(), path);
}

}  // namespace

bool is_rosbag2(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) return fs::is_regular_file(fs::path(path) / kMetadataFile, ec);
  return fs::is_regular_file(path, ec) && (is_sqlite(path) || is_mcap(path));
}

namespace rosbag2_internal {

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

}  // namespace rosbag2_internal

}  // namespace tsgraphs::ros2_bag
