#include "cli/map_file.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <utility>

namespace pvtap::analyzer {

RegisterMapResult read_register_map_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    // The system's reason (no such file, permission denied), not a word on the map.
    MapDiagnostic d{path, 0, 0, std::string("cannot open the file: ") + std::strerror(errno)};
    return RegisterMapResult::failure({std::move(d)});
  }
  std::ostringstream text;
  text << in.rdbuf();
  return load_register_map(text.str(), path);
}

}  // namespace pvtap::analyzer
