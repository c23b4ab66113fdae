#pragma once
/// Loop closure: candidates near in space and far in accumulated travel (hdl_graph_slam's
/// rule), each verified by registering the keyframes' clouds with a fitness check.
#include <functional>
#include <map>
#include <optional>
#include <vector>

#include "tsgraphs/core/point_cloud.hpp"
#include "tsgraphs/graph/situational_graph.hpp"
#include "tsgraphs/registration/registration.hpp"
#include "tsgraphs/core/config_fields.hpp"

namespace tsgraphs::graph {

struct LoopClosureConfig {
  double max_distance = 5.0;
  double min_travel = 8.0;
  double min_loop_interval = 5.0;
  int max_candidates = 3;
  double max_fitness = 0.03;
  double min_inlier_ratio = 0.7;  ///< ...and this share of points found a close match (the figure that
                                  ///< tells a wrong place: floor and ceiling match anywhere indoors)
  double max_correction = 2.0;
  double min_facing_share = 0.01;  ///< reject when fewer than this share of the matched points lie on
                                   ///< surfaces facing the direction they pin least (a corridor without its
                                   ///< ends in view: the match slides along it); 0.01 of a keyframe's few
                                   ///< thousand matched points is a door frame or a wall's end
  double max_reverse_disagreement =
      0.02;  ///< reject when registering the pair the other way round, from the
             ///< inverse guess, ends farther than this from the first match (m): a match
             ///< with one optimum is found from both sides alike; partial overlap with
             ///< repeated shelves gave two wrong loops 0.02-0.05 m apart, right ones < 0.01
  registration::RegistrationConfig registration;  ///< GICP settings for the check

  template <class V>
  void visit(V& v) {
    v("max_distance", max_distance, between(0.0, 1000.0),
      "m; candidates nearer than this to the new keyframe");
    v("min_travel", min_travel, between(0.0, 1e6), "m; and at least this far back in travelled distance");
    v("min_loop_interval", min_loop_interval, between(0.0, 1e6),
      "m travelled since the last accepted loop before trying again");
    v("max_candidates", max_candidates, between(0, 100), "nearest candidates registered per keyframe");
    v("max_fitness", max_fitness, above(0.0, 100.0),
      "m^2; accept when the mean squared match distance is below this");
    v("min_inlier_ratio", min_inlier_ratio, between(0.0, 1.0),
      "and this share of points found a close match");
    v("max_correction", max_correction, above(0.0, 1000.0),
      "m; reject when registration moves the guess more than this");
    v("min_facing_share", min_facing_share, between(0.0, 1.0),
      "reject when fewer matched points than this share face the direction they pin least (a corridor's "
      "length: the match slides)");
    v("max_reverse_disagreement", max_reverse_disagreement, above(0.0, 1000.0),
      "m; reject when the pair registered the other way round (from the inverse guess) ends farther than "
      "this from the first match");
    v.section("registration", registration, "GICP");
  }
};

class LoopDetector {
 public:
  explicit LoopDetector(LoopClosureConfig config = {});
  /// Keyframe ids that may close a loop with keyframe `id`, nearest first (never a retired one).
  std::vector<int> candidates(const SituationalGraph& graph, int id) const;
  /// Tries the candidates of keyframe `id`; returns the verified loop edge (from = the older
  /// keyframe, to = `id`, measurement T_from_to) or nothing. `cloud_of(k)` gives keyframe k's
  /// cloud in its own frame.
  std::optional<BetweenEdge> detect(const SituationalGraph& graph, int id,
                                    const std::function<const PointCloud&(int)>& cloud_of);
  /// Registers keyframe `id` with each of `candidates` in turn (another proposer's, e.g.
  /// room_loop_closure.hpp); the first that passes the checks gives the loop edge. Not held
  /// back by min_loop_interval, but an accepted loop restarts it.
  std::optional<BetweenEdge> verify(const SituationalGraph& graph, int id, const std::vector<int>& candidates,
                                    const std::function<const PointCloud&(int)>& cloud_of);
  const LoopClosureConfig& config() const { return config_; }

 private:
  /// The keyframes' clouds prepared for registration, from the cache or made (at once) and
  /// cached. The candidates of consecutive keyframes are mostly the same, so the newest
  /// preparations are kept (kPreparedKept); the results never depend on the cache, only the time.
  std::vector<registration::PreparedCloud> prepared(const std::vector<int>& ids,
                                                    const std::function<const PointCloud&(int)>& cloud_of);

  LoopClosureConfig config_;
  double last_loop_travel_ = -1e18;
  struct Prepared {
    registration::PreparedCloud cloud;
    long last_use = 0;  ///< the value of uses_ when it was last asked for
  };
  std::map<int, Prepared> prepared_;  // keyframe id -> its prepared cloud
  long uses_ = 0;
};

}  // namespace tsgraphs::graph
