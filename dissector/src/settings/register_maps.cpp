#include "settings/register_maps.h"

#include <wsutil/filesystem.h>
#include <wsutil/report_message.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "settings/map_file.h"

namespace pvtap::dissector {
namespace {

namespace fs = std::filesystem;

constexpr const char* kUserMapFolder = "pvtap";

std::array<RegisterMap, kDialectCount> g_maps;

RegisterMap& slot_of(Dialect d) {
  return g_maps[static_cast<std::size_t>(d)];
}

fs::path user_map_folder() {
  char* path = get_persconffile_path(kUserMapFolder, FALSE);
  fs::path folder(path != nullptr ? path : "");
  g_free(path);
  return folder;
}

std::vector<fs::path> user_map_files(const fs::path& folder) {
  std::vector<fs::path> files;
  std::error_code ec;
  if (folder.empty() || !fs::is_directory(folder, ec)) return files;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().extension() == ".toml" && it->is_regular_file(ec)) files.push_back(it->path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

void report_unloaded(const fs::path& file, const std::string& why) {
  report_warning("pvtap: the register map %s was not loaded; the dissector goes on without it.\n%s",
                 file.c_str(), why.c_str());
}

// Files stack in name order (stack_register_map, as pvtap's --map files do in their order).
void apply_user_map(const fs::path& file, const RegisterMap& user) {
  RegisterMap& current = slot_of(user.dialect());
  RegisterMapResult stacked = stack_register_map(current, user);
  if (!stacked) {
    report_unloaded(file, stacked.error_text());
    return;
  }
  current = stacked.value();
}

void load_user_map(const fs::path& file) {
  RegisterMapResult loaded = read_map_file(file);
  if (!loaded) {
    report_unloaded(file, loaded.error_text());
    return;
  }
  apply_user_map(file, loaded.value());
}

}  // namespace

void load_register_maps() {
  for (Dialect d : kAllDialects) {
    slot_of(d) = builtin_register_map(d);
  }
  try {
    for (const fs::path& file : user_map_files(user_map_folder())) load_user_map(file);
  } catch (const std::exception& e) {
    report_warning("pvtap: reading the user register maps failed: %s", e.what());
  }
}

const RegisterMap& effective_map(Dialect d) {
  return slot_of(d);
}

}  // namespace pvtap::dissector
