// read_register_map_file: the analyzer reads a map file and the core parses its text.
#include "cli/map_files.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "small_register_map.h"

namespace pvtap::analyzer {
namespace {

TEST(MapFile, LoadsFromAFileAndNamesMissingFiles) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "pvtap_map_file_test_small.toml";
  {
    std::ofstream out(path);
    out << kSmallRegisterMap;
  }
  RegisterMapResult good = read_register_map_file(path.string());
  ASSERT_TRUE(good) << good.error_text();
  EXPECT_EQ(good->source_name(), path.string());
  EXPECT_EQ(good->size(), 1u);
  std::filesystem::remove(path);

  RegisterMapResult missing = read_register_map_file(path.string());
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error_text().find(path.string() + ": cannot open the file"), std::string::npos)
      << missing.error_text();
}

}  // namespace
}  // namespace pvtap::analyzer
