/// Fuzz target: KITTI files, each reader on the same bytes: a velodyne .bin scan, poses.txt
/// (3x4 rows) and times.txt.
#include "fuzz_support.hpp"
#include "tsgraphs/io/kitti.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tsgraphs;
  const std::string scan = fuzz::input_file(data, size, "000000.bin");
  fuzz::only_input_errors("read_kitti_bin", [&] { io::read_kitti_bin(scan); });
  const std::string text = fuzz::input_file(data, size, "poses.txt");
  fuzz::only_input_errors("read_kitti_poses", [&] { io::read_kitti_poses(text); });
  fuzz::only_input_errors("read_times", [&] { io::read_times(text); });
  fuzz::only_input_errors("fields_on_first_line", [&] { io::fields_on_first_line(text); });
  return 0;
}
