#include "segmentation_images.hpp"

#include <cstdio>
#include <filesystem>
#include <utility>

#include "tsgraphs/io/atomic_write.hpp"
#include "tsgraphs/io/room_labels_writer.hpp"

namespace tsgraphs::app {

SegmentationImages::SegmentationImages(std::string folder) : folder_(std::move(folder)) {
  std::filesystem::create_directories(folder_);
  index_ = "image,keyframe,stamp,level,origin_x,origin_y,cell,cols,rows,spaces\n";
}

void SegmentationImages::write_new(const pipeline::Pipeline& slam) {
  const room_layer::RoomLayer& layer = slam.room_layer();
  const rooms::RoomSegmentation* seg = layer.last_segmentation();
  if (seg == nullptr || layer.segmentations() == written_) return;
  written_ = layer.segmentations();
  char name[32];
  std::snprintf(name, sizeof name, "%04zu.png", written_);
  const GridFrame& f = seg->frame;
  io::write_file_atomic(folder_ + "/" + name,
                        io::encode_png(io::room_label_image(seg->label, f.cols, f.rows)));
  const auto& keyframes = slam.graph().keyframes();
  char line[256];
  std::snprintf(line, sizeof line, "%s,%zu,%.3f,%d,%.3f,%.3f,%.3f,%d,%d,%zu\n", name,
                keyframes.empty() ? 0 : keyframes.size() - 1,
                keyframes.empty() ? 0.0 : keyframes.back().stamp, layer.last_segmentation_level(),
                f.origin.x(), f.origin.y(), f.resolution, f.cols, f.rows, seg->spaces.size());
  index_ += line;
}

void SegmentationImages::close() const { io::write_file_atomic(folder_ + "/index.csv", index_); }

}  // namespace tsgraphs::app
