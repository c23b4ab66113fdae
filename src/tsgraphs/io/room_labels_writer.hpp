#pragma once
/// Room-label images written: a segmentation's labels as one colour per room, black where no
/// room (the colour convention of room_labels.hpp, which reads them back). segment-map's --out
/// and run's --segmentations write them.
#include <vector>

#include "tsgraphs/io/image.hpp"

namespace tsgraphs::io {

/// The labels (width * height, row 0 at the bottom, -1 none) as an RGB image (row 0 at the
/// top): room k's colour is a hue a golden angle from room k - 1's, never black.
Image room_label_image(const std::vector<int>& labels, int width, int height);

}  // namespace tsgraphs::io
