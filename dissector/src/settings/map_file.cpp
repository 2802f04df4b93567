#include "settings/map_file.h"

#include <glib.h>

#include <optional>
#include <string>
#include <utility>

namespace pvtap::dissector {
namespace {

std::optional<std::string> file_text(const std::filesystem::path& file) {
  gchar* contents = nullptr;
  gsize length = 0;
  if (!g_file_get_contents(file.c_str(), &contents, &length, nullptr)) return std::nullopt;
  std::string text(contents, length);
  g_free(contents);
  return text;
}

}  // namespace

RegisterMapResult read_map_file(const std::filesystem::path& file) {
  const std::optional<std::string> text = file_text(file);
  if (!text) {
    MapDiagnostic d{file.string(), 0, 0, "cannot open the file"};
    return RegisterMapResult::failure({std::move(d)});
  }
  return load_register_map(*text, file.string());
}

}  // namespace pvtap::dissector
