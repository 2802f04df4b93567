#include "cli/map_file.h"

#include <fstream>
#include <sstream>
#include <utility>

namespace pvtap::analyzer {

RegisterMapResult read_register_map_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    MapDiagnostic d{path, 0, 0, "cannot open the file"};
    return RegisterMapResult::failure({std::move(d)});
  }
  std::ostringstream text;
  text << in.rdbuf();
  return load_register_map(text.str(), path);
}

}  // namespace pvtap::analyzer
