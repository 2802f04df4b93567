// The section names of --help, the same whichever CLI11 pvtap is built with.
#pragma once

#include <CLI/CLI.hpp>

namespace pvtap::analyzer {

// CLI11 2.5 renamed the help sections "Options:" and "Positionals:" to "OPTIONS:" and
// "POSITIONALS:". help2man makes a man page's OPTIONS section only of "Options:", and people
// and the bash completion read one help on every release, so pvtap keeps the older names.
// Call it once every option of `app` and its subcommands has been added.
void keep_help_section_names(CLI::App& app);

}  // namespace pvtap::analyzer
