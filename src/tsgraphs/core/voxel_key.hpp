#pragma once
/// The one key of every hashed grid: a 2-D cell or a 3-D voxel from its integer indices, and
/// the hash for open-addressing tables of such keys. Callers compute the indices (floor of the
/// coordinate over the cell size); only the packing is shared, so that all grids agree on it.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include <Eigen/Core>

namespace tsgraphs {

/// Bits per axis of a voxel key: indices in [-2^20, 2^20), +-1e6 voxels, far beyond any LiDAR
/// range at useful voxel sizes. Indices outside wrap (far-apart voxels share a key).
inline constexpr int kVoxelKeyBits = 21;

/// Key of voxel (a, b, c): 21 bits each, offset so that negative indices pack too.
inline std::uint64_t voxel_key(std::int64_t a, std::int64_t b, std::int64_t c) {
  constexpr std::int64_t kOffset = std::int64_t{1} << (kVoxelKeyBits - 1);
  constexpr std::uint64_t kMask = (std::uint64_t{1} << kVoxelKeyBits) - 1;
  auto axis = [](std::int64_t v) { return static_cast<std::uint64_t>(v + kOffset) & kMask; };
  return axis(a) | (axis(b) << kVoxelKeyBits) | (axis(c) << (2 * kVoxelKeyBits));
}

/// The voxel indices of a key made by voxel_key (the inverse for indices in range).
inline Eigen::Vector3i voxel_of_key(std::uint64_t key) {
  constexpr std::int64_t kOffset = std::int64_t{1} << (kVoxelKeyBits - 1);
  constexpr std::uint64_t kMask = (std::uint64_t{1} << kVoxelKeyBits) - 1;
  auto axis = [&](int shift) {
    return static_cast<int>(static_cast<std::int64_t>((key >> shift) & kMask) - kOffset);
  };
  return {axis(0), axis(kVoxelKeyBits), axis(2 * kVoxelKeyBits)};
}

/// Key of the voxel of edge 1 / inv_size that holds p.
inline std::uint64_t voxel_key(const Eigen::Vector3f& p, double inv_size) {
  auto index = [&](float v) { return static_cast<std::int64_t>(std::floor(v * inv_size)); };
  return voxel_key(index(p.x()), index(p.y()), index(p.z()));
}

/// Key of 2-D cell (column, row): the two indices' low 32 bits side by side.
inline std::uint64_t cell_key(std::int64_t column, std::int64_t row) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(column)) << 32) |
         static_cast<std::uint32_t>(row);
}

/// Hash of a packed key for open-addressing tables: a full-avalanche mix (splitmix64's
/// finaliser). Neighbouring voxels differ in few bits; with the identity hash of std::hash
/// they pile into the same slots of a power-of-two table.
struct KeyHash {
  std::size_t operator()(std::uint64_t k) const {
    k ^= k >> 30;
    k *= 0xBF58476D1CE4E5B9ULL;
    k ^= k >> 27;
    k *= 0x94D049BB133111EBULL;
    k ^= k >> 31;
    return static_cast<std::size_t>(k);
  }
};

}  // namespace tsgraphs
