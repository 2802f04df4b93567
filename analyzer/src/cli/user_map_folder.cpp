#include "cli/user_map_folder.h"

#include <algorithm>
#include <cstdlib>

namespace pvtap::analyzer {

namespace fs = std::filesystem;

fs::path user_map_folder() {
  // The XDG rule: an empty or relative XDG_CONFIG_HOME is ignored.
  const char* config = std::getenv("XDG_CONFIG_HOME");
  if (config != nullptr && fs::path(config).is_absolute()) return fs::path(config) / "pvtap/maps";
  const char* home = std::getenv("HOME");
  if (home != nullptr && *home != '\0') return fs::path(home) / ".config/pvtap/maps";
  return {};
}

std::vector<std::string> user_map_files(const fs::path& folder) {
  std::vector<std::string> files;
  std::error_code ec;
  if (folder.empty() || !fs::is_directory(folder, ec)) return files;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().extension() == ".toml" && it->is_regular_file(ec)) {
      files.push_back(it->path().string());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace pvtap::analyzer
