// PCD reading speed (io/pcd.cpp) for each encoding, on a real HDL-32 scan (69,088 points,
// x y z intensity float32, tests/data/hdl32_pair) written as ascii, binary and
// binary_compressed (LZF, as PCL writes it). Bytes per second are of the file read.
//   ./build/bench/bench_pcd --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>
#include <lzf.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tsgraphs/io/pcd.hpp"

using namespace tsgraphs;

namespace {

const std::string kScan = std::string(TSGRAPHS_BENCH_DATA_DIR) + "/hdl32_pair/251370668.pcd";

std::string header(std::size_t n, const std::string& data) {
  std::ostringstream h;
  h << "VERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\nWIDTH " << n
    << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << n << "\nDATA " << data << "\n";
  return h.str();
}

/// The scan in `encoding`, written to a file of the temporary folder; its path.
std::string scan_file(const std::string& encoding) {
  const PointCloud cloud = io::read_pcd(kScan);
  const std::size_t n = cloud.size();
  std::string text;
  if (encoding == "binary") text = io::encode_pcd(cloud);
  if (encoding == "ascii") {
    std::ostringstream body;
    body.precision(9);
    for (std::size_t i = 0; i < n; ++i) {
      body << cloud.points[i].x() << ' ' << cloud.points[i].y() << ' ' << cloud.points[i].z() << ' '
           << cloud.intensity[i] << '\n';
    }
    text = header(n, "ascii") + body.str();
  }
  if (encoding == "binary_compressed") {
    std::string soa(n * 16, '\0');  // field after field
    for (std::size_t i = 0; i < n; ++i) {
      const float v[4] = {cloud.points[i].x(), cloud.points[i].y(), cloud.points[i].z(), cloud.intensity[i]};
      for (int f = 0; f < 4; ++f) std::memcpy(soa.data() + (f * n + i) * 4, &v[f], 4);
    }
    std::string lzf(soa.size() + soa.size() / 16 + 64, '\0');
    const unsigned compressed = lzf_compress(soa.data(), static_cast<unsigned>(soa.size()), lzf.data(),
                                             static_cast<unsigned>(lzf.size()));
    const unsigned words[2] = {compressed, static_cast<unsigned>(soa.size())};
    text = header(n, "binary_compressed") + std::string(reinterpret_cast<const char*>(words), 8) +
           lzf.substr(0, compressed);
  }
  const std::string path =
      (std::filesystem::temp_directory_path() / ("tsgraphs_bench_" + encoding + ".pcd")).string();
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

void BM_ReadPcd(benchmark::State& state, const std::string& encoding) {
  const std::string path = scan_file(encoding);
  std::size_t points = 0;
  for (auto _ : state) {
    points = io::read_pcd(path).size();
    benchmark::DoNotOptimize(points);
  }
  const auto bytes = static_cast<double>(std::filesystem::file_size(path));
  state.SetBytesProcessed(static_cast<int64_t>(bytes) * state.iterations());
  state.counters["points"] = static_cast<double>(points);
  state.counters["file_MB"] = bytes / 1e6;
  std::filesystem::remove(path);
}

}  // namespace

BENCHMARK_CAPTURE(BM_ReadPcd, ascii, std::string("ascii"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadPcd, binary, std::string("binary"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadPcd, binary_compressed, std::string("binary_compressed"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
