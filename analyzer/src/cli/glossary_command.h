// The `glossary` subcommand: pvtap's words for what it finds, with their meanings.
#pragma once

#include <string>

namespace CLI {
class App;
}  // namespace CLI

namespace pvtap::analyzer {

struct GlossaryCommandLine {
  std::string format = "text";  // text, jsonl or markdown
};

// Adds `glossary` to the program's command line; parsed values land in `command`.
CLI::App* add_glossary_command(CLI::App& app, GlossaryCommandLine& command);

// Prints the glossary; returns the exit status.
int run_glossary(const GlossaryCommandLine& command);

}  // namespace pvtap::analyzer
