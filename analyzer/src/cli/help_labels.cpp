#include "cli/help_labels.h"

#include <string>

namespace pvtap::analyzer {
namespace {

void name_option_groups(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    if (option->get_group() == "OPTIONS") option->group("Options");
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
    if (sub->get_group() == "SUBCOMMANDS") sub->group("Subcommands");
    name_option_groups(*sub);
  }
}

}  // namespace

void keep_help_section_names(CLI::App& app) {
  // Unknown labels are printed as they are, so on CLI11 2.4 this changes nothing.
  app.get_formatter()->label("POSITIONALS", "Positionals");
  name_option_groups(app);
}

}  // namespace pvtap::analyzer
