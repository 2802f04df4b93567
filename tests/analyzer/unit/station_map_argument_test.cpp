// read_station_map_argument: which --map values give a map to stations, and which stations.
#include "cli/map_files.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <vector>

namespace pvtap::analyzer {
namespace {

TEST(StationMapArgument, ReadsOneStationOrAList) {
  const auto one = read_station_map_argument("10=meter.toml");
  ASSERT_TRUE(one);
  EXPECT_EQ(one->stations, std::vector<std::uint8_t>{10});
  EXPECT_EQ(one->path, "meter.toml");
  EXPECT_EQ(one->problem, "");
  const auto list = read_station_map_argument("1,247=maps/a=b.toml");
  ASSERT_TRUE(list);
  EXPECT_EQ(list->stations, (std::vector<std::uint8_t>{1, 247}));
  EXPECT_EQ(list->path, "maps/a=b.toml");  // only the first '=' separates
}

TEST(StationMapArgument, PlainFilesAreNotStationMaps) {
  EXPECT_FALSE(read_station_map_argument("meter.toml"));
  EXPECT_FALSE(read_station_map_argument("./site=2.toml"));  // a '/' before the '='
  // A file in the working folder whose name holds '=' stays a file.
  const std::filesystem::path before = std::filesystem::current_path();
  std::filesystem::current_path(std::filesystem::temp_directory_path());
  std::ofstream("pvtap_x=1.toml") << "dialect = \"modbus\"\n";
  const bool read_as_file = !read_station_map_argument("pvtap_x=1.toml");
  std::filesystem::remove("pvtap_x=1.toml");
  std::filesystem::current_path(before);
  EXPECT_TRUE(read_as_file);
  EXPECT_TRUE(read_station_map_argument("pvtap_x=1.toml"));  // gone: a station list again
}

TEST(StationMapArgument, BadStationsSayWhy) {
  EXPECT_EQ(read_station_map_argument("0=m.toml")->problem,
            "station 0 is outside 1 to 247 (0 is the broadcast address)");
  EXPECT_EQ(read_station_map_argument("248=m.toml")->problem, "station 248 is outside 1 to 247");
  EXPECT_EQ(read_station_map_argument("99999999999=m.toml")->problem,
            "'99999999999' is not a station address (1 to 247)");
  EXPECT_EQ(read_station_map_argument("meter=m.toml")->problem,
            "'meter' is not a station address (1 to 247)");
  EXPECT_EQ(read_station_map_argument("10,,11=m.toml")->problem,
            "'' is not a station address (1 to 247)");
  EXPECT_EQ(read_station_map_argument("+10=m.toml")->problem,
            "'+10' is not a station address (1 to 247)");
  EXPECT_EQ(read_station_map_argument("10=")->problem, "no map FILE after '='");
}

}  // namespace
}  // namespace pvtap::analyzer
