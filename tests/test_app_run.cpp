// `tsgraphs run` and `tsgraphs eval` as a user calls them: the outputs, and bad input
// (a missing odometry line, a truncated scan, NaN points, an empty scan, a bad parameter file).
// ctest: slow (seconds a test: simulated runs or generated buildings)
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <cstdlib>
#include <Eigen/Geometry>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <tuple>

#include "small_room_test_support.hpp"
#include "test_support.hpp"
#include "tsgraphs/eval/room_metrics.hpp"
#include "tsgraphs/mcap/mcap.hpp"
#include "tsgraphs/ros1_bag/ros_bag.hpp"
#include "tsgraphs/ros2_bag/rosbag2.hpp"
#include "tsgraphs/io/image.hpp"
#include "tsgraphs/io/sequence_folder.hpp"
#include "tsgraphs/io/tum.hpp"
#include "tsgraphs/pipeline/pipeline.hpp"
#include "tsgraphs/pipeline/run_outputs.hpp"
#include "tsgraphs/pipeline/sequence_runner.hpp"
#include "tsgraphs/report/foxglove_export.hpp"

namespace fs = std::filesystem;
using namespace tsgraphs;

namespace {

using test::cli;
using test::read_file;

class RunCli : public test::TempDirTest {
 protected:
  // One simulated sequence shared by the tests of this file (copied where a test damages it).
  static void SetUpTestSuite() {
    base_ = test::fresh_temp_dir("run_cli_base");
    std::string err;
    ASSERT_TRUE(test::simulate_small_room(base_, &err)) << err;
  }
  static void TearDownTestSuite() { fs::remove_all(base_); }

  fs::path copy_sequence() const {
    const fs::path seq = dir_ / "seq";
    fs::copy(base_ / "seq", seq, fs::copy_options::recursive);
    return seq;
  }
  static fs::path base_;
};
fs::path RunCli::base_;

using PlyVertex = io::MapVertex;

// map.ply's vertices, written as doubles (UTM coordinates to the millimetre).
std::vector<PlyVertex> read_map_ply(const fs::path& file) {
  EXPECT_NE(read_file(file).find("property double x\nproperty double y\nproperty double z\n"),
            std::string::npos);
  return io::read_map_ply(file.string());
}

}  // namespace

TEST_F(RunCli, WritesEveryOutputAndEvalFillsTheTrajectoryFigures) {
  const fs::path seq = base_ / "seq", out = dir_ / "run";
  std::string err;
  ASSERT_EQ(cli("-q run " + seq.string() + " --out " + out.string(), &err), 0) << err;
  for (const char* f : {"trajectory.txt", "scene_graph.json", "map.ply", "timings.csv", "params.yaml",
                        "run_info.json", "report.html", "birdseye.svg"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  const auto traj = io::read_tum((out / "trajectory.txt").string());
  const auto gt = io::read_tum((seq / "groundtruth.txt").string());
  ASSERT_EQ(traj.size(), gt.size());
  const auto graph = nlohmann::json::parse(read_file(out / "scene_graph.json"));
  EXPECT_GE(graph["keyframes"].size(), 10u);
  EXPECT_GE(graph["planes"].size(), 4u);
  EXPECT_GE(graph["traversable_nodes"].size(), 50u);
  EXPECT_EQ(read_file(out / "map.ply").rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
  // Rooms are graph nodes with their wall factors, on the one floor.
  ASSERT_GE(graph["room_nodes"].size(), 1u);
  EXPECT_EQ(graph["floors"].size(), 1u);
  const auto& graph_edges = graph["edges"];
  EXPECT_TRUE(std::any_of(graph_edges.begin(), graph_edges.end(),
                          [](const auto& e) { return e["type"] == "room_planes"; }));
  EXPECT_TRUE(std::any_of(graph_edges.begin(), graph_edges.end(),
                          [](const auto& e) { return e["type"] == "floor_room"; }));
  EXPECT_TRUE(std::any_of(graph["rooms"].begin(), graph["rooms"].end(),
                          [](const auto& r) { return r["node"].is_number(); }));
  // Each room carries the free space it was extracted from, near its footprint.
  for (const auto& r : graph["rooms"]) {
    ASSERT_GE(r["free_space"].size(), 10u) << r.dump();
    const auto& c = r["rect"]["center"];
    const auto& p = r["free_space"][0];
    EXPECT_LT(std::hypot(p[0].get<double>() - c[0].get<double>(), p[1].get<double>() - c[1].get<double>()),
              std::hypot(r["rect"]["size"][0].get<double>(), r["rect"]["size"][1].get<double>()));
  }
  // map.ply draws the rooms (cyan or orange outlines) and the floor node (a yellow cross).
  int outline = 0, floor_cross = 0;
  for (const PlyVertex& v : read_map_ply(out / "map.ply")) {
    if ((v.r == 0 && v.g == 200 && v.b == 255) || (v.r == 255 && v.g == 150 && v.b == 0)) ++outline;
    if (v.r == 255 && v.g == 255 && v.b == 0) ++floor_cross;
  }
  EXPECT_GE(outline, 100);  // 0.05 m apart round rooms metres wide
  EXPECT_GE(floor_cross, 20);

  ASSERT_EQ(cli("-q eval " + out.string() + " --seq " + seq.string(), &err), 0) << err;
  const auto m = nlohmann::json::parse(read_file(out / "metrics.json"));
  ASSERT_TRUE(m["trajectory"]["ate_rmse"].is_number());
  EXPECT_LE(m["trajectory"]["ate_rmse"].get<double>(), m["trajectory"]["odom_ate_rmse"].get<double>());
  EXPECT_TRUE(m["pgo"]["t_pgo_s"].is_number());
  EXPECT_GE(m["pgo"]["n_optimisations"].get<double>(), 1.0);
  EXPECT_TRUE(m["walls"]["mean_dist_err"].is_number());
  ASSERT_TRUE(m["ground"]["precision"].is_number());
  EXPECT_GE(m["ground"]["precision"].get<double>(), 0.9);
  EXPECT_GE(m["ground"]["recall"].get<double>(), 0.9);
  EXPECT_TRUE(m["consistency"]["N1st"].is_number());
  const auto events = io::read_room_events((out / "rooms_events.jsonl").string());
  EXPECT_GE(events.size(), 1u);
  for (const auto& e : events) EXPECT_GT(e.rect.size.x() * e.rect.size.y(), 1.0);
  EXPECT_TRUE(m["speed"]["rtf"].is_number());

  // The same input and config give the same outputs, byte for byte (timings aside).
  const fs::path out2 = dir_ / "run2";
  ASSERT_EQ(cli("-q run " + seq.string() + " --out " + out2.string(), &err), 0) << err;
  EXPECT_EQ(read_file(out / "trajectory.txt"), read_file(out2 / "trajectory.txt"));
  EXPECT_EQ(read_file(out / "scene_graph.json"), read_file(out2 / "scene_graph.json"));
}

TEST_F(RunCli, BaselineModeExtractsOnTheTimerAndIsRecordedInParams) {
  const fs::path seq = base_ / "seq", out = dir_ / "run";
  std::string err;
  ASSERT_EQ(
      cli("-q run " + seq.string() + " --out " + out.string() + " --free-space esdf --room-trigger timer",
          &err),
      0)
      << err;
  const std::string params = read_file(out / "params.yaml");
  EXPECT_NE(params.find("free_space_method: esdf"), std::string::npos);
  EXPECT_NE(params.find("room_trigger: timer"), std::string::npos);
  const auto events = io::read_room_events((out / "rooms_events.jsonl").string());
  ASSERT_GE(events.size(), 2u);
  // At most one extraction per period of the 1 s grid that starts at the first keyframe (t = 0).
  for (std::size_t i = 1; i < events.size(); ++i)
    EXPECT_GT(std::floor(events[i].t + 1e-9), std::floor(events[i - 1].t + 1e-9));
  for (const auto& e : events) EXPECT_NEAR(std::remainder(e.rect.yaw, M_PI / 2), 0.0, 1e-9);  // map axes only
  EXPECT_EQ(
      cli("-q run " + seq.string() + " --out " + (dir_ / "bad").string() + " --free-space voxblox", &err), 2);
  EXPECT_FALSE(fs::exists(dir_ / "bad"));
}

TEST_F(RunCli, SegmentationsAreWrittenAsLabelImagesAndChangeNoOtherOutput) {
  const fs::path seq = base_ / "seq", plain = dir_ / "plain", out = dir_ / "run";
  std::string err;
  ASSERT_EQ(cli("-q run " + seq.string() + " --out " + plain.string(), &err), 0) << err;
  ASSERT_EQ(cli("-q run " + seq.string() + " --out " + out.string() + " --segmentations", &err), 0) << err;
  for (const char* f : {"trajectory.txt", "scene_graph.json", "rooms_events.jsonl", "map.ply"})
    EXPECT_EQ(read_file(out / f), read_file(plain / f)) << f;
  EXPECT_FALSE(fs::exists(plain / "segmentations"));
  // index.csv: a header and a line per image, naming it; each image the raster it gives.
  std::istringstream index(read_file(out / "segmentations" / "index.csv"));
  std::string line;
  ASSERT_TRUE(std::getline(index, line));
  EXPECT_EQ(line, "image,keyframe,stamp,level,origin_x,origin_y,cell,cols,rows,spaces");
  int images = 0, with_rooms = 0;
  while (std::getline(index, line)) {
    std::vector<std::string> field;
    std::stringstream parts(line);
    for (std::string v; std::getline(parts, v, ',');) field.push_back(v);
    ASSERT_EQ(field.size(), 10u) << line;
    const io::Image img = io::read_image((out / "segmentations" / field[0]).string());
    EXPECT_EQ(img.width, std::stoi(field[7]));
    EXPECT_EQ(img.height, std::stoi(field[8]));
    EXPECT_EQ(img.channels, 3);
    const bool coloured =
        std::any_of(img.samples.begin(), img.samples.end(), [](std::uint8_t v) { return v > 0; });
    EXPECT_EQ(coloured, std::stoi(field[9]) > 0) << line;
    with_rooms += coloured ? 1 : 0;
    ++images;
  }
  EXPECT_GT(images, 0);
  EXPECT_GT(with_rooms, 0);
  EXPECT_EQ(static_cast<std::size_t>(images) + 1,
            static_cast<std::size_t>(std::distance(fs::directory_iterator(out / "segmentations"), {})));
}

TEST_F(RunCli, ParallelRunEqualsOneScanAtATime) {
  // `run` reads and prepares scans on several threads; feeding them one by one must agree.
  const fs::path seq = base_ / "seq", out = dir_ / "run";
  std::string err;
  ASSERT_EQ(cli("-q --threads 2 run " + seq.string() + " --out " + out.string(), &err), 0) << err;
  const io::SequenceReader reader(seq.string());
  pipeline::Pipeline slam;
  pipeline::measure_platform(reader, false, slam);  // as `run` does before its first scan
  for (std::size_t i = 0; i < reader.size(); ++i)
    slam.process(i, reader.info().times[i], reader.scan(i), reader.info().odometry[i]);
  slam.finish();
  const auto traj = io::read_tum((out / "trajectory.txt").string());
  const std::vector<Pose3> mine = slam.trajectory();
  ASSERT_EQ(traj.size(), mine.size());
  for (std::size_t i = 0; i < mine.size(); ++i)
    ASSERT_TRUE(traj[i].pose.isApprox(mine[i], 1e-12)) << "scan " << i;
  EXPECT_EQ(read_file(out / "scene_graph.json"), pipeline::scene_graph_json(slam));
}

TEST_F(RunCli, KittiFolderOfTheSameScansGivesTheSameTrajectory) {
  // The sequence as a KITTI odometry folder: velodyne/NNNNNN.bin, poses.txt (3x4 rows), times.txt.
  const fs::path seq = base_ / "seq", kitti = dir_ / "kitti";
  fs::create_directories(kitti / "velodyne");
  const io::SequenceReader reader(seq.string());
  std::ofstream poses(kitti / "poses.txt"), times(kitti / "times.txt");
  poses.precision(17);
  times.precision(17);
  for (std::size_t i = 0; i < reader.size(); ++i) {
    fs::copy_file(seq / "scans" / (io::scan_stem(i) + ".bin"),
                  kitti / "velodyne" / (io::scan_stem(i) + ".bin"));
    const Pose3& T = reader.info().odometry[i];
    for (int r = 0; r < 3; ++r)
      poses << T.linear()(r, 0) << " " << T.linear()(r, 1) << " " << T.linear()(r, 2) << " "
            << T.translation()(r) << (r < 2 ? " " : "\n");
    times << reader.info().times[i] << "\n";
  }
  poses.close();
  times.close();
  std::string err;
  ASSERT_EQ(cli("-q run " + seq.string() + " --out " + (dir_ / "a").string(), &err), 0) << err;
  ASSERT_EQ(cli("-q run " + kitti.string() + " --out " + (dir_ / "b").string(), &err), 0) << err;
  const auto a = io::read_tum((dir_ / "a" / "trajectory.txt").string());
  const auto b = io::read_tum((dir_ / "b" / "trajectory.txt").string());
  ASSERT_EQ(a.size(), b.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_NEAR(a[i].t, b[i].t, 1e-9);
    worst = std::max(worst, (a[i].pose.translation() - b[i].pose.translation()).norm());
  }
  EXPECT_LT(worst, 1e-6);
  const auto ga = nlohmann::json::parse(read_file(dir_ / "a" / "scene_graph.json"));
  const auto gb = nlohmann::json::parse(read_file(dir_ / "b" / "scene_graph.json"));
  EXPECT_EQ(ga["rooms"].size(), gb["rooms"].size());
  EXPECT_TRUE(fs::exists(dir_ / "b" / "report.html"));

  // Neither a folder nor --scans; folder options on a sequence folder: one clear error each.
  EXPECT_EQ(cli("-q run --out " + (dir_ / "c").string(), &err), 2);
  EXPECT_NE(err.find("give one of SEQ_DIR, --scans GLOB or --bag FILE"), std::string::npos) << err;
  EXPECT_EQ(cli("-q run " + seq.string() + " --poses x.txt --out " + (dir_ / "c").string(), &err), 2);
  EXPECT_NE(err.find("sequence folder has its own poses"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir_ / "c"));
}

TEST_F(RunCli, BagOfTheSequenceInEachCompressionGivesTheSameRun) {
  const fs::path seq = base_ / "seq";
  std::string err;
  ASSERT_EQ(cli("-q run " + seq.string() + " --out " + (dir_ / "folder").string(), &err), 0) << err;
  const auto folder = io::read_tum((dir_ / "folder" / "trajectory.txt").string());
  const auto folder_graph = nlohmann::json::parse(read_file(dir_ / "folder" / "scene_graph.json"));
  // The sensor 0.3 m above and 0.1 m ahead of the base: /odom is the base, /tf_static the offset.
  const Pose3 sensor_to_base = make_pose(Eigen::Vector3d(0.1, 0.0, 0.3), 0.2);
  const io::SequenceReader reader(seq.string());
  for (const auto& [name, compression] :
       {std::pair{"none", ros1_bag::BagCompression::none}, std::pair{"bz2", ros1_bag::BagCompression::bz2},
        std::pair{"lz4", ros1_bag::BagCompression::lz4}}) {
    SCOPED_TRACE(name);
    const fs::path bag = dir_ / (std::string(name) + ".bag"), out = dir_ / (std::string("bag_") + name);
    ros1_bag::write_bag(reader, bag.string(), compression, sensor_to_base);
    ASSERT_EQ(cli("-q run --bag " + bag.string() + " --points-topic /points --odom-topic /odom --out " +
                      out.string(),
                  &err),
              0)
        << err;
    const auto from_bag = io::read_tum((out / "trajectory.txt").string());
    ASSERT_EQ(from_bag.size(), folder.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < folder.size(); ++i) {
      EXPECT_NEAR(from_bag[i].t, folder[i].t, 1e-6);
      worst = std::max(worst, (from_bag[i].pose.translation() - folder[i].pose.translation()).norm());
    }
    EXPECT_LT(worst, 1e-6);  // the tf_static offset undone exactly, up to floating-point noise
    const auto graph = nlohmann::json::parse(read_file(out / "scene_graph.json"));
    EXPECT_EQ(graph["rooms"].size(), folder_graph["rooms"].size());
    EXPECT_EQ(graph["planes"].size(), folder_graph["planes"].size());
  }

  // bag-info lists the topics; the ground truth rides along as PoseStamped.
  std::string out;
  ASSERT_EQ(test::run_tsgraphs("bag-info " + (dir_ / "lz4.bag").string(), &out, &err), 0) << err;
  EXPECT_NE(out.find("/points"), std::string::npos) << out;
  EXPECT_NE(out.find("sensor_msgs/PointCloud2"), std::string::npos) << out;
  EXPECT_NE(out.find("nav_msgs/Odometry"), std::string::npos) << out;
  EXPECT_NE(out.find("geometry_msgs/PoseStamped"), std::string::npos) << out;

  // convert: the bag back to a sequence folder, which runs as the original did.
  ASSERT_EQ(cli("-q convert --bag " + (dir_ / "lz4.bag").string() +
                    " --points-topic /points --odom-topic /odom --out " + (dir_ / "converted").string(),
                &err),
            0)
      << err;
  ASSERT_EQ(
      cli("-q run " + (dir_ / "converted").string() + " --out " + (dir_ / "converted_run").string(), &err), 0)
      << err;
  const auto converted = io::read_tum((dir_ / "converted_run" / "trajectory.txt").string());
  ASSERT_EQ(converted.size(), folder.size());
  EXPECT_LT((converted.back().pose.translation() - folder.back().pose.translation()).norm(), 1e-6);

  // simulate --bag writes the same scans straight from the scene (and no sequence folder).
  ASSERT_EQ(cli("-q simulate " + (base_ / "room.yaml").string() + " --bag " + (dir_ / "sim.bag").string() +
                    " --compression none",
                &err),
            0)
      << err;
  ASSERT_EQ(test::run_tsgraphs("bag-info " + (dir_ / "sim.bag").string(), &out, &err), 0) << err;
  EXPECT_NE(out.find(std::to_string(reader.size()) + " msgs"), std::string::npos) << out;
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_EQ(e.path().string().find("sequence-tmp"), std::string::npos);

  // PoseStamped odometry (the ground truth) and an explicit --sensor-to-base work too.
  ASSERT_EQ(
      cli("-q run --bag " + (dir_ / "lz4.bag").string() +
              " --points-topic /points --odom-topic /groundtruth --sensor-to-base 0 0 0 0 0 0 1 --out " +
              (dir_ / "gt").string(),
          &err),
      0)
      << err;
  const auto gt = io::read_tum((dir_ / "gt" / "trajectory.txt").string());
  EXPECT_NEAR((gt.back().pose.translation() - reader.info().groundtruth.back().translation()).norm(), 0.0,
              0.05);

  // A missing topic, a topic of another type, a truncated bag: one error line, exit 2, no run folder.
  const std::string bag = (dir_ / "none.bag").string();
  EXPECT_EQ(cli("-q run --bag " + bag + " --points-topic /velodyne_points --odom-topic /odom --out " +
                    (dir_ / "x").string(),
                &err),
            2);
  EXPECT_NE(err.find("no topic /velodyne_points (topics: /groundtruth, /odom, /points, /tf_static)"),
            std::string::npos)
      << err;
  EXPECT_EQ(
      cli("-q run --bag " + bag + " --points-topic /odom --odom-topic /odom --out " + (dir_ / "x").string(),
          &err),
      2);
  EXPECT_NE(err.find("/odom is nav_msgs/Odometry, expected sensor_msgs/PointCloud2"), std::string::npos)
      << err;
  const std::string bytes = read_file(bag);
  std::ofstream(dir_ / "cut.bag", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  EXPECT_EQ(cli("-q run --bag " + (dir_ / "cut.bag").string() +
                    " --points-topic /points --odom-topic /odom --out " + (dir_ / "x").string(),
                &err),
            2);
  EXPECT_NE(err.find("cut.bag"), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_FALSE(fs::exists(dir_ / "x"));
}

// Issue 19: the same sequence as a ROS 1 bag, a rosbag2 SQLite file and rosbag2 MCAP files in
// each chunk compression (and rosbag2 folders, plain and under rosbag2's own compression) runs to
// byte-identical outputs.
TEST_F(RunCli, Ros2BagsInEveryStorageRunAsTheRos1Bag) {
  const io::SequenceReader reader((base_ / "seq").string());
  const Pose3 sensor_to_base = make_pose(Eigen::Vector3d(0.1, 0.0, 0.3), 0.2);
  std::string err;
  const auto run_bag = [&](const fs::path& bag, const std::string& name) {
    const fs::path out = dir_ / ("run_" + name);
    EXPECT_EQ(cli("-q run --bag " + bag.string() + " --points-topic /points --odom-topic /odom --out " +
                      out.string(),
                  &err),
              0)
        << name << ": " << err;
    return out;
  };
  ros1_bag::write_bag(reader, (dir_ / "ros1.bag").string(), ros1_bag::BagCompression::lz4, sensor_to_base);
  const fs::path ros1 = run_bag(dir_ / "ros1.bag", "ros1");
  std::vector<std::pair<std::string, fs::path>> bags;
  ros2_bag::write_rosbag2(reader, (dir_ / "ros2.db3").string(), ros2_bag::Rosbag2Storage::sqlite,
                          mcap::Compression::none, sensor_to_base);
  bags.emplace_back("sqlite", dir_ / "ros2.db3");
  for (const auto& [name, c] :
       {std::pair{"none", mcap::Compression::none}, std::pair{"lz4", mcap::Compression::lz4},
        std::pair{"zstd", mcap::Compression::zstd}}) {
    const fs::path bag = dir_ / (std::string("ros2_") + name + ".mcap");
    ros2_bag::write_rosbag2(reader, bag.string(), ros2_bag::Rosbag2Storage::mcap, c, sensor_to_base);
    bags.emplace_back(std::string("mcap_") + name, bag);
  }
  // A rosbag2 folder: metadata.yaml naming its file.
  fs::create_directories(dir_ / "folder_bag");
  fs::copy_file(dir_ / "ros2_zstd.mcap", dir_ / "folder_bag" / "folder_bag_0.mcap");
  std::ofstream(dir_ / "folder_bag" / "metadata.yaml")
      << "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: mcap\n  relative_file_paths:\n"
         "    - folder_bag_0.mcap\n  compression_format: \"\"\n  compression_mode: \"\"\n";
  bags.emplace_back("folder", dir_ / "folder_bag");
  // And as rosbag2 writes one: metadata.yaml and NAME_0.db3.
  ros2_bag::write_rosbag2(reader, (dir_ / "written_bag").string(), ros2_bag::Rosbag2Storage::sqlite,
                          mcap::Compression::none, sensor_to_base);
  ASSERT_TRUE(fs::exists(dir_ / "written_bag" / "written_bag_0.db3"));
  bags.emplace_back("written_folder", dir_ / "written_bag");
  // Under rosbag2's own compression: the SQLite file compressed whole, MCAP messages one by one.
  ros2_bag::write_rosbag2(reader, (dir_ / "file_bag").string(), ros2_bag::Rosbag2Storage::sqlite,
                          mcap::Compression::none, sensor_to_base, ros2_bag::Rosbag2Compression::file);
  bags.emplace_back("zstd_file_folder", dir_ / "file_bag");
  ros2_bag::write_rosbag2(reader, (dir_ / "message_bag").string(), ros2_bag::Rosbag2Storage::mcap,
                          mcap::Compression::none, sensor_to_base, ros2_bag::Rosbag2Compression::message);
  bags.emplace_back("zstd_message_folder", dir_ / "message_bag");
  for (const auto& [name, bag] : bags) {
    SCOPED_TRACE(name);
    const fs::path out = run_bag(bag, name);
    for (const char* f : {"trajectory.txt", "scene_graph.json", "rooms_events.jsonl"})
      EXPECT_EQ(read_file(out / f), read_file(ros1 / f)) << f;
  }
  std::string out;
  ASSERT_EQ(test::run_tsgraphs("bag-info " + (dir_ / "ros2.db3").string(), &out, &err), 0) << err;
  EXPECT_NE(out.find("sensor_msgs/msg/PointCloud2"), std::string::npos) << out;
  EXPECT_NE(out.find(std::to_string(reader.size()) + " msgs"), std::string::npos) << out;
  // simulate --bag by extension, and a compression the format has not.
  ASSERT_EQ(
      cli("-q simulate " + (base_ / "room.yaml").string() + " --bag " + (dir_ / "sim.mcap").string(), &err),
      0)
      << err;
  ASSERT_EQ(test::run_tsgraphs("bag-info " + (dir_ / "sim.mcap").string(), &out, &err), 0) << err;
  EXPECT_NE(out.find("nav_msgs/msg/Odometry"), std::string::npos) << out;
  EXPECT_EQ(cli("-q simulate " + (base_ / "room.yaml").string() + " --bag " + (dir_ / "sim.db3").string() +
                    " --compression zstd",
                &err),
            2);
  EXPECT_NE(err.find("--compression: zstd is not a ros2-sqlite compression (none, zstd-file, zstd-message)"),
            std::string::npos)
      << err;
  EXPECT_FALSE(fs::exists(dir_ / "sim.db3"));
  EXPECT_EQ(cli("-q simulate " + (base_ / "room.yaml").string() + " --bag " + (dir_ / "sim.db3").string() +
                    " --compression zstd-message",
                &err),
            2);
  EXPECT_NE(err.find("sim.db3: --compression zstd-message is rosbag2's own, for a bag folder"),
            std::string::npos)
      << err;
  EXPECT_FALSE(fs::exists(dir_ / "sim.db3"));
  // A damaged MCAP (cut in its data section) and a missing topic: one line naming the file, exit 2, no run.
  const std::string bytes = read_file(dir_ / "ros2_zstd.mcap");
  std::ofstream(dir_ / "cut.mcap", std::ios::binary) << bytes.substr(0, bytes.size() / 3);
  EXPECT_EQ(cli("-q run --bag " + (dir_ / "cut.mcap").string() +
                    " --points-topic /points --odom-topic /odom --out " + (dir_ / "run_cut").string(),
                &err),
            2);
  EXPECT_EQ(err.rfind("tsgraphs: error: " + (dir_ / "cut.mcap").string() + ": ", 0), 0u) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_FALSE(fs::exists(dir_ / "run_cut"));
  EXPECT_EQ(cli("-q run --bag " + (dir_ / "ros2.db3").string() + " --points-topic /scan --out " +
                    (dir_ / "run_topic").string(),
                &err),
            2);
  EXPECT_NE(err.find("no topic /scan (topics: /groundtruth, /odom, /points, /tf_static)"), std::string::npos)
      << err;
}

namespace {

// What `value` breaks of JSON Schema `schema` ("" when nothing): type, properties, required,
// additionalProperties false, items, minimum, maximum, maxItems: what the export's schemas use.
std::string schema_error(const nlohmann::json& schema, const nlohmann::json& value,
                         const std::string& at = "$") {
  if (schema.contains("type")) {
    const std::string t = schema["type"];
    const bool ok = t == "object"    ? value.is_object()
                    : t == "array"   ? value.is_array()
                    : t == "string"  ? value.is_string()
                    : t == "boolean" ? value.is_boolean()
                    : t == "integer" ? value.is_number_integer()
                    : t == "number"  ? value.is_number()
                                     : false;
    if (!ok) return at + ": not " + t;
  }
  if (schema.contains("minimum") && value.get<double>() < schema["minimum"].get<double>())
    return at + ": below minimum";
  if (schema.contains("maximum") && value.get<double>() > schema["maximum"].get<double>())
    return at + ": above maximum";
  if (schema.contains("maxItems") && value.size() > schema["maxItems"].get<std::size_t>())
    return at + ": too many items";
  if (value.is_object()) {
    for (const auto& r : schema.value("required", nlohmann::json::array()))
      if (!value.contains(r.get<std::string>())) return at + ": no " + r.get<std::string>();
    for (const auto& [key, v] : value.items()) {
      if (schema.contains("properties") && schema["properties"].contains(key)) {
        if (std::string e = schema_error(schema["properties"][key], v, at + "." + key); !e.empty()) return e;
      } else if (schema.value("additionalProperties", true) == false) {
        return at + ": unknown field " + key;
      }
    }
  }
  if (value.is_array() && schema.contains("items")) {
    for (std::size_t i = 0; i < value.size(); ++i)
      if (std::string e = schema_error(schema["items"], value[i], at + "[" + std::to_string(i) + "]");
          !e.empty())
        return e;
  }
  return "";
}

}  // namespace

// Issue 19: a run as an MCAP file for Foxglove: every message is JSON of its channel's schema,
// the poses and room extractions at their times, the map and nodes whole.
TEST_F(RunCli, ExportWritesARunForFoxgloveWithEveryMessageOfItsSchema) {
  const fs::path run = dir_ / "run", out = dir_ / "run.mcap";
  std::string err;
  ASSERT_EQ(cli("-q run " + (base_ / "seq").string() + " --out " + run.string(), &err), 0) << err;
  ASSERT_EQ(cli("-q export " + run.string() + " --mcap " + out.string(), &err), 0) << err;
  const mcap::Reader mcap(out.string());
  EXPECT_TRUE(mcap.indexed());
  std::map<std::string, std::size_t> count;
  std::map<std::string, nlohmann::json> last;
  mcap.read_each(mcap.messages(), [&](const mcap::MessageRef& ref, const mcap::Message& m) {
    const mcap::Channel& c = mcap.channels().at(ref.channel_id);
    const mcap::Schema& s = mcap.schemas().at(c.schema_id);
    EXPECT_EQ(c.message_encoding, "json");
    EXPECT_EQ(s.encoding, "jsonschema");
    const auto message = nlohmann::json::parse(m.data);
    EXPECT_EQ(schema_error(nlohmann::json::parse(s.data), message), "") << c.topic;
    EXPECT_EQ(s.name, c.topic == "/tf" ? "foxglove.FrameTransform"
                      : c.topic == "/map" || c.topic == "/traversable_nodes" || c.topic == "/free_space"
                          ? "foxglove.PointCloud"
                          : "foxglove.SceneUpdate");
    ++count[c.topic];
    last[c.topic] = message;
  });
  const auto trajectory = io::read_tum((run / "trajectory.txt").string());
  const auto events = io::read_room_events((run / "rooms_events.jsonl").string());
  const auto graph = io::read_scene_graph((run / "scene_graph.json").string());
  ASSERT_GE(events.size(), 1u);
  EXPECT_EQ(count["/tf"], trajectory.size());
  EXPECT_EQ(count["/rooms"], events.size());
  EXPECT_EQ(count["/map"], 1u);
  EXPECT_EQ(count["/scene"], 1u);
  // The node cloud holds every node, 12 bytes each (base64: 4 characters per 3 bytes).
  EXPECT_EQ(last["/traversable_nodes"]["data"].get<std::string>().size(),
            (12 * graph.traversable_nodes.size() + 2) / 3 * 4);
  std::size_t free_points = 0;
  for (const auto& r : graph.rooms) free_points += r.free_space.size();
  ASSERT_GT(free_points, 0u);
  EXPECT_EQ(last["/free_space"]["data"].get<std::string>().size(), (16 * free_points + 2) / 3 * 4);
  EXPECT_EQ(last["/tf"]["translation"]["x"].get<double>(), trajectory.back().pose.translation().x());
  // A schema check that could fail: a field Foxglove does not know.
  nlohmann::json bad = last["/tf"];
  bad["extra"] = 1;
  EXPECT_NE(schema_error(nlohmann::json::parse(report::foxglove_schema("foxglove.FrameTransform")), bad), "");
  // Issue 52: a damaged map.ply is one error line naming it and the byte, and nothing is written:
  // a header saying float over the body of doubles, and a NaN.
  const std::string map = read_file(run / "map.ply");
  const std::string double_property = "property double", end_header = "end_header\n";
  std::string floats = map;
  for (std::size_t at; (at = floats.find(double_property)) != std::string::npos;)
    floats.replace(at, double_property.size(), "property float");
  std::string nan = map;
  const double not_a_number = std::nan("");
  nan.replace(map.find(end_header) + end_header.size(), sizeof not_a_number,
              reinterpret_cast<const char*>(&not_a_number), sizeof not_a_number);
  for (const auto& [damaged, what] :
       {std::pair{floats, std::string(" bytes after the last of the header's ")},
        std::pair{nan, std::string(": 'vertex[0].x' must be finite")}}) {
    std::ofstream(run / "map.ply", std::ios::binary) << damaged;
    EXPECT_EQ(cli("-q export " + run.string() + " --mcap " + (dir_ / "damaged.mcap").string(), &err), 2);
    EXPECT_EQ(err.find("tsgraphs: error: " + (run / "map.ply").string() + ": "), 0u) << err;
    EXPECT_NE(err.find(what), std::string::npos) << err;
    EXPECT_NE(err.find("byte "), std::string::npos) << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_FALSE(fs::exists(dir_ / "damaged.mcap"));
  }
  // A run folder without its files is one error line.
  fs::remove(run / "map.ply");
  EXPECT_EQ(cli("-q export " + run.string() + " --mcap " + (dir_ / "again.mcap").string(), &err), 2);
  EXPECT_NE(err.find("map.ply"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir_ / "again.mcap"));
}

// Issue 52: no command writes over, into or round what it reads (each of these did, exit 0).
TEST_F(RunCli, OutputsNeverOverwriteTheCommandsInputs) {
  const fs::path seq = copy_sequence(), scene = base_ / "room.yaml";
  std::string err;
  const auto refused = [&](const std::string& args, const std::string& what) {
    EXPECT_EQ(cli("-q " + args, &err), 2) << args;
    EXPECT_NE(err.find(what), std::string::npos) << args << ": " << err;
    EXPECT_EQ(err.find("tsgraphs: error: "), err.rfind("tsgraphs: error: ")) << err;  // one error line
  };
  refused("convert " + seq.string() + " --out " + seq.string(),
          "--out: " + seq.string() + " is the command's input");
  refused("convert " + seq.string() + " --out " + (seq / "again").string(),
          "lies inside the command's input");
  refused("run " + seq.string() + " --out " + (seq / "run").string(), "lies inside the command's input");
  refused("run " + seq.string() + " --out " + dir_.string(), "holds the command's input");
  EXPECT_TRUE(fs::exists(seq / "scene.yaml"));
  EXPECT_FALSE(fs::exists(seq / "again"));
  EXPECT_FALSE(fs::exists(seq / "run"));
  const std::string scene_text = read_file(scene);
  refused("draw-scene " + scene.string() + " --out " + scene.string(), "is the command's input");
  refused("simulate " + scene.string() + " --out " + scene.string(), "is the command's input");
  EXPECT_EQ(read_file(scene), scene_text);
  const fs::path run = dir_ / "run";
  ASSERT_EQ(cli("-q run " + seq.string() + " --out " + run.string(), &err), 0) << err;
  const std::string graph = read_file(run / "scene_graph.json");
  refused("export " + run.string() + " --mcap " + (run / "scene_graph.json").string(),
          "lies inside the command's input");
  EXPECT_EQ(read_file(run / "scene_graph.json"), graph);
}

// Issue 52: a run whose every scan is skipped ended with exit 0 and 0 keyframes.
TEST_F(RunCli, ARunWhoseEveryScanIsSkippedIsRefusedWithNothingWritten) {
  const fs::path seq = copy_sequence();
  for (const auto& e : fs::directory_iterator(seq / "scans")) std::ofstream(e.path(), std::ios::trunc);
  std::string err;
  EXPECT_EQ(cli("-q run " + seq.string() + " --out " + (dir_ / "run").string(), &err), 2);
  EXPECT_NE(err.find("tsgraphs: error: " + seq.string() + ": no scan could be used: all "), std::string::npos)
      << err;
  EXPECT_FALSE(fs::exists(dir_ / "run"));
}

// Issue 52: a layer empty in every keyframe of a run shorter than the warning's run of
// keyframes (diagnostics.empty_layer_keyframes) said nothing.
TEST_F(RunCli, ALayerEmptyInEveryKeyframeOfAShortRunIsSaid) {
  write_file("params.yaml", "plane_extraction:\n  min_inliers: 10000000\n");
  std::string err;
  ASSERT_EQ(cli("-q run " + (base_ / "seq").string() + " --out " + (dir_ / "run").string() + " --config " +
                    (dir_ / "params.yaml").string(),
                &err),
            0)
      << err;
  EXPECT_NE(err.find("tsgraphs: warning: no wall in any of the run's "), std::string::npos) << err;
  EXPECT_NE(err.find("no vertical plane of plane_extraction.min_inliers (10000000) points"),
            std::string::npos)
      << err;
}

TEST_F(RunCli, MissingOdometryLineIsAnErrorNamingTheFileAndNoOutput) {
  const fs::path seq = copy_sequence();
  std::string odom = read_file(seq / "odom.txt");
  odom.erase(odom.rfind('\n', odom.size() - 2) + 1);  // drop the last line
  std::ofstream(seq / "odom.txt") << odom;
  std::string err;
  EXPECT_EQ(cli("-q run " + seq.string() + " --out " + (dir_ / "run").string(), &err), 2);
  EXPECT_NE(err.find("odom.txt"), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_FALSE(fs::exists(dir_ / "run"));
}

// Issue 18: an odometry line 5e7 m off ended in "internal error: std::bad_alloc" (exit 1).
TEST_F(RunCli, OdometryJumpNoPlatformMakesIsRefusedBeforeTheRun) {
  const fs::path seq = copy_sequence();
  std::istringstream lines(read_file(seq / "odom.txt"));
  std::ostringstream odom;
  int n = 0;
  for (std::string line; std::getline(lines, line); ++n) {
    if (n == 2)
      line.replace(line.find(' '), line.find(' ', line.find(' ') + 1) - line.find(' '),
                   " 5e7");  // x of scan 2
    odom << line << "\n";
  }
  std::ofstream(seq / "odom.txt") << odom.str();
  std::string err;
  EXPECT_EQ(cli("-q run " + seq.string() + " --out " + (dir_ / "run").string(), &err), 2);
  EXPECT_NE(err.find(seq.string() + ": odometry of scan 2 "), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_FALSE(fs::exists(dir_ / "run"));
}

// Issue 18: map.ply stored float32, so a run at UTM coordinates was quantised to 1/4 m, and the
// pipeline's own float32 points with it (its trajectory 2.4 cm from the same run elsewhere). The
// pipeline runs in a map frame at the first pose rounded to whole kilometres and the outputs are
// moved back: the sequence 512 km east and 4,012 km north gives the run of the sequence 345 m
// east and north, moved by the whole kilometres (a shift of its own, 345 m, changes a run by
// millimetres: float rounding, amplified by registration).
TEST_F(RunCli, ASequenceAtUtmCoordinatesRunsAsNearTheOrigin) {
  const auto shifted = [&](const std::string& name, const Eigen::Vector3d& by) {
    const fs::path seq = dir_ / name;
    fs::copy(base_ / "seq", seq, fs::copy_options::recursive);
    std::istringstream lines(read_file(seq / "odom.txt"));
    std::ostringstream odom;
    for (std::string line; std::getline(lines, line);) {
      std::istringstream v(line);
      double t, x, y, z, qx, qy, qz, qw;
      EXPECT_TRUE(v >> t >> x >> y >> z >> qx >> qy >> qz >> qw) << line;
      char text[400];
      std::snprintf(text, sizeof text, "%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", t, x + by.x(),
                    y + by.y(), z + by.z(), qx, qy, qz, qw);
      odom << text;
    }
    std::ofstream(seq / "odom.txt") << odom.str();
    return seq;
  };
  const Eigen::Vector3d near(345.0, 345.0, 0.0), kilometres(512000.0, 4012000.0, 0.0);
  std::string err;
  const fs::path here = dir_ / "run_near", far = dir_ / "run_far";
  ASSERT_EQ(cli("-q run " + shifted("near", near).string() + " --out " + here.string(), &err), 0) << err;
  ASSERT_EQ(cli("-q run " + shifted("far", near + kilometres).string() + " --out " + far.string(), &err), 0)
      << err;

  const auto a = io::read_tum((here / "trajectory.txt").string()),
             b = io::read_tum((far / "trajectory.txt").string());
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_LT((b[i].pose.translation() - kilometres - a[i].pose.translation()).norm(), 1e-6) << "scan " << i;
  }
  // The map: the same points, not on float32's grid at 4e6 m (every y a multiple of 1/4 m).
  const std::vector<PlyVertex> ma = read_map_ply(here / "map.ply"), mb = read_map_ply(far / "map.ply");
  ASSERT_GT(ma.size(), 1000u);
  ASSERT_EQ(ma.size(), mb.size());
  std::size_t on_quarter_grid = 0;
  for (std::size_t i = 0; i < ma.size(); ++i) {
    ASSERT_LT((mb[i].p - kilometres - ma[i].p).norm(), 1e-6) << "vertex " << i;
    ASSERT_EQ(std::tie(mb[i].r, mb[i].g, mb[i].b), std::tie(ma[i].r, ma[i].g, ma[i].b)) << "vertex " << i;
    on_quarter_grid += std::fmod(mb[i].p.y(), 0.25) == 0.0;
  }
  EXPECT_LT(on_quarter_grid, mb.size() / 10);
  // The scene graph: the same planes (n.x + d = 0 moved), rooms and levels.
  const io::SceneGraph ga = io::read_scene_graph((here / "scene_graph.json").string());
  const io::SceneGraph gb = io::read_scene_graph((far / "scene_graph.json").string());
  ASSERT_EQ(ga.planes.size(), gb.planes.size());
  for (std::size_t i = 0; i < ga.planes.size(); ++i) {
    EXPECT_NEAR(gb.planes[i].d + gb.planes[i].n.dot(kilometres), ga.planes[i].d, 1e-6) << "plane " << i;
  }
  ASSERT_EQ(ga.rooms.size(), gb.rooms.size());
  ASSERT_GE(ga.rooms.size(), 1u);
  for (std::size_t i = 0; i < ga.rooms.size(); ++i) {
    EXPECT_LT((gb.rooms[i].rect.center - kilometres.head<2>() - ga.rooms[i].rect.center).norm(), 1e-6)
        << "room " << i;
  }
  ASSERT_EQ(ga.traversable_nodes.size(), gb.traversable_nodes.size());
  EXPECT_EQ(ga.levels, gb.levels);
}

TEST_F(RunCli, TruncatedNaNAndEmptyScansAreSkippedWithWarningsAndNoNaNPose) {
  const fs::path seq = copy_sequence();
  // Scan 3: truncated mid-point. Scans 0 (a keyframe) and 5 (none): every point NaN. Scan 20: empty.
  {
    const fs::path p = seq / "scans" / "000003.bin";
    fs::resize_file(p, fs::file_size(p) - 6);
  }
  for (const char* name : {"000000.bin", "000005.bin"}) {
    const fs::path p = seq / "scans" / name;
    std::string bin = read_file(p);
    const float nan = std::nanf("");
    for (std::size_t i = 0; i + 16 <= bin.size(); i += 16) std::memcpy(&bin[i], &nan, sizeof nan);
    std::ofstream(p, std::ios::binary) << bin;
  }
  std::ofstream(seq / "scans" / "000020.bin", std::ios::binary | std::ios::trunc);
  fs::remove(seq / "scans" / "000020.label");
  const fs::path out = dir_ / "run";
  std::string err;
  ASSERT_EQ(cli("-q run " + seq.string() + " --out " + out.string(), &err), 0) << err;
  EXPECT_NE(err.find("000003.bin"), std::string::npos) << err;
  EXPECT_NE(err.find("scan 0: no finite point (all NaN): skipped"), std::string::npos) << err;
  EXPECT_NE(err.find("scan 5: no finite point (all NaN): skipped"), std::string::npos) << err;
  EXPECT_NE(err.find("scan 20: empty scan: skipped"), std::string::npos) << err;
  const auto traj = io::read_tum((out / "trajectory.txt").string());  // read_tum rejects non-finite values
  EXPECT_EQ(traj.size(), io::read_tum((seq / "odom.txt").string()).size());
}

TEST_F(RunCli, BadParameterFileAndUnrelatedOutputFolderAreRefused) {
  std::string err;
  const std::string params = write_file("p.yaml", "keyframes:\n  delta_trans: 1.0\n  delta_trns: 2.0\n");
  EXPECT_EQ(
      cli("-q run " + (base_ / "seq").string() + " --out " + (dir_ / "run").string() + " --config " + params,
          &err),
      2);
  EXPECT_NE(err.find("p.yaml:3: unknown key 'keyframes.delta_trns'"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir_ / "run"));

  fs::create_directories(dir_ / "mine");
  write_file("mine/notes.txt", "keep me");
  EXPECT_EQ(cli("-q run " + (base_ / "seq").string() + " --out " + (dir_ / "mine").string(), &err), 2);
  EXPECT_EQ(read_file(dir_ / "mine" / "notes.txt"), "keep me");

  EXPECT_EQ(cli("-q eval " + (dir_ / "nothing").string(), &err), 2);
  EXPECT_NE(err.find("nothing"), std::string::npos) << err;
}

TEST_F(RunCli, ArgumentsOutOfRangeAreRefusedBeforeAnyWork) {
  // Each of these ran to the end and failed there (exit 1), or overflowed, or wrote without end.
  std::string err;
  const std::string seq = (base_ / "seq").string();
  EXPECT_EQ(cli("-q run " + seq + " --out /", &err), 2);
  EXPECT_NE(err.find("--out: / holds the command's input"), std::string::npos) << err;
  EXPECT_EQ(
      cli("-q run " + seq + " --out " + (dir_ / "run").string() + " --sensor-to-base nan 0 0 0 0 0 1", &err),
      2);
  EXPECT_NE(err.find("--sensor-to-base: x y z must be finite"), std::string::npos) << err;
  EXPECT_EQ(
      cli("-q run " + seq + " --out " + (dir_ / "run").string() + " --sensor-to-base 0 0 0 0 0 0 0", &err),
      2);
  EXPECT_NE(err.find("must be a rotation"), std::string::npos) << err;
  EXPECT_EQ(cli("-q run --scans '" + seq + "/scans/*.bin' --out " + (dir_ / "run").string() +
                    " --scan-period 1e308",
                &err),
            2);
  EXPECT_NE(err.find("--scan-period"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir_ / "run"));
  const std::string scene = (base_ / "room.yaml").string();
  EXPECT_EQ(cli("-q simulate " + scene + " --laps 10000 --out " + (dir_ / "sim").string(), &err), 2);
  EXPECT_NE(err.find("--laps: the path makes 1.49e+06 scans, more than 1000000"), std::string::npos) << err;
  EXPECT_EQ(cli("-q simulate " + scene + " --laps 100000 --out " + (dir_ / "sim").string(), &err), 2);
  EXPECT_NE(err.find("--laps: must be a whole number in [1, 10000], not '100000'"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir_ / "sim"));
}

// A scene whose voxel map lies in another folder: its sequence carries the map, so it runs
// where it was written, and again after it is moved and the map's folder is gone.
TEST_F(RunCli, ASequenceCarriesItsSceneVoxelMapsAndRunsAfterItMoves) {
  fs::create_directories(dir_ / "scenes");
  fs::create_directories(dir_ / "maps");
  std::ostringstream pcd;
  pcd << "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n";
  std::ostringstream points;
  int n = 0;
  for (int i = 0; i <= 20; ++i) {
    for (int k = 0; k < 20; ++k, ++n) points << 3.0 + 0.1 * i << " 3.0 " << 0.05 + 0.1 * k << "\n";
  }
  pcd << "WIDTH " << n << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << n << "\nDATA ascii\n"
      << points.str();
  std::ofstream(dir_ / "maps" / "wall.pcd") << pcd.str();
  std::string scene = test::kSmallRoomScene;
  scene.replace(
      scene.find("trajectory:"), 11,
      "voxel_maps:\n  - {file: ../maps/wall.pcd, voxel_size: 0.1, level: L0, label: wall}\ntrajectory:");
  std::ofstream(dir_ / "scenes" / "room.yaml") << scene;
  const fs::path seq = dir_ / "seq", moved = dir_ / "elsewhere" / "seq";
  std::string err;
  ASSERT_EQ(cli("-q simulate " + (dir_ / "scenes" / "room.yaml").string() + " --laps 1 --out " + seq.string(),
                &err),
            0)
      << err;
  EXPECT_TRUE(fs::exists(seq / "voxel_maps" / "0_wall.pcd"));
  ASSERT_EQ(cli("-q run " + seq.string() + " --out " + (dir_ / "run1").string(), &err), 0) << err;
  fs::create_directories(moved.parent_path());
  fs::rename(seq, moved);
  fs::remove_all(dir_ / "maps");
  fs::remove_all(dir_ / "scenes");
  ASSERT_EQ(cli("-q run " + moved.string() + " --out " + (dir_ / "run2").string(), &err), 0) << err;
  ASSERT_EQ(cli("-q eval " + (dir_ / "run2").string() + " --seq " + moved.string(), &err), 0) << err;
  // The copy of the scene still has the wall the map adds: simulating it again gives the same scans.
  ASSERT_EQ(
      cli("-q simulate " + (moved / "scene.yaml").string() + " --laps 1 --out " + (dir_ / "again").string(),
          &err),
      0)
      << err;
  EXPECT_EQ(read_file(moved / "scans" / "000010.bin"), read_file(dir_ / "again" / "scans" / "000010.bin"));
}
