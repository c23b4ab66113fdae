#pragma once
/// The sequence folder (docs/scene-format.md, "Sequence folder"): what `simulate` writes and
/// what `run` reads. KITTI-layout scans, SemanticKITTI labels, TUM poses.
#include <memory>
#include <string>
#include <vector>

#include "tsgraphs/core/point_cloud.hpp"
#include "tsgraphs/io/scan_sequence.hpp"
#include "tsgraphs/io/sequence_info.hpp"
#include "tsgraphs/io/tum.hpp"

namespace tsgraphs::io {

/// Writes a sequence folder under a temporary name; `commit` renames it into place, so a
/// killed run leaves nothing that looks like a complete sequence.
class SequenceWriter {
 public:
  /// An existing `dir` is replaced only if it is empty or holds an earlier sequence.
  explicit SequenceWriter(const std::string& dir);
  ~SequenceWriter();
  /// Writes scans/NNNNNN.bin (and .label when the cloud has labels).
  void write_scan(std::size_t index, const PointCloud& cloud);
  /// Writes the text files and moves the folder into place. Scan count must match.
  void commit(const SequenceInfo& info);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Reads a sequence folder, checking that the files agree with each other.
class SequenceReader : public ScanSequence {
 public:
  /// Throws InputError naming the file and line for a missing or inconsistent folder: one
  /// scan file, scans/NNNNNN.bin, for each line of times.txt and odom.txt, and no other.
  explicit SequenceReader(const std::string& dir);
  std::size_t size() const override { return info_.times.size(); }
  const SequenceInfo& info() const override { return info_; }
  const std::string& dir() const override { return dir_; }
  /// Path of scene.yaml, "" for real data.
  std::string scene_path() const override;
  /// Reads scan `index` with intensity, and labels when the .label file exists.
  PointCloud scan(std::size_t index) const override;
  /// From the .bin's size and its first finite point, the .label's size and whether a .time
  /// is there: the same InputErrors as scan() for what it checks, without building the cloud.
  ScanPresence presence(std::size_t index) const override;
  bool presence_is_cheap() const override { return true; }

 private:
  std::string dir_;
  SequenceInfo info_;
};

/// "scans/000042.bin"-style name of a scan file without extension.
std::string scan_stem(std::size_t index);

}  // namespace tsgraphs::io
