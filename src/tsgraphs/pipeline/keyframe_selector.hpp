#pragma once
/// Step 3: a new keyframe after enough motion since the last one.
#include <optional>

#include "tsgraphs/core/pose.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::pipeline {

struct KeyframeConfig {
  double delta_trans = 1.0;
  double delta_angle_deg = 20.0;

  template <class V>
  void visit(V& v) {
    v("delta_trans", delta_trans, above(0.0, 1000.0), "m of motion since the last keyframe (S-Graphs: 2.0)");
    v("delta_angle_deg", delta_angle_deg, above(0.0, 360.0),
      "deg of rotation since the last keyframe (S-Graphs: 2 rad)");
  }
};

class KeyframeSelector {
 public:
  explicit KeyframeSelector(KeyframeConfig config = {}) : config_(config) {}
  /// True for the first pose and whenever `odom` has moved or turned enough since the last
  /// accepted keyframe; the caller then calls accept(odom).
  bool is_keyframe(const Pose3& odom) const;
  void accept(const Pose3& odom) { last_ = odom; }

 private:
  KeyframeConfig config_;
  std::optional<Pose3> last_;
};

}  // namespace tsgraphs::pipeline
