#include "tsgraphs/io/subsampled_sequence.hpp"

#include <stdexcept>

namespace tsgraphs::io {

SubsampledSequence::SubsampledSequence(const ScanSequence& source, std::size_t every)
    : source_(source), every_(every), info_(source.info()) {
  if (every == 0) throw std::invalid_argument("SubsampledSequence: every must be >= 1");
  const SequenceInfo& in = source.info();
  const auto keep = [every](const auto& all) {
    std::remove_cv_t<std::remove_reference_t<decltype(all)>> out;
    for (std::size_t i = 0; i < all.size(); i += every) out.push_back(all[i]);
    return out;
  };
  info_.times = keep(in.times);
  info_.odometry = keep(in.odometry);
  info_.groundtruth = keep(in.groundtruth);
}

}  // namespace tsgraphs::io
