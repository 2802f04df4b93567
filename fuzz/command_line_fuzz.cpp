// Fuzz target command_line: `pvtap audit` and `pvtap sniff` option parsing (CLI11 with pvtap's
// options, validators and choices) and apply_choices() on arbitrary argument lists
// (NUL-separated in the input). A bad command line must end as a CLI11 parse error (the usage
// error of exit status 2), never as another exception or a crash.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "cli/audit_command.h"
#include "cli/common_options.h"
#include "cli/sniff_command.h"
#include "fuzz_input.h"

namespace {

// The arguments after the program name, in the reverse order CLI11's parse(vector&) wants.
std::vector<std::string> reversed_arguments(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> args = pvtap::fuzz::nul_separated_arguments(data, size);
  std::reverse(args.begin(), args.end());
  return args;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace pvtap::analyzer;
  CLI::App app{"pvtap", "pvtap"};
  app.require_subcommand(1);
  AuditOptions audit_options;
  CLI::App* audit = add_audit_command(app, audit_options);
  SniffCommandLine sniff_command;
  CLI::App* sniff = add_sniff_command(app, sniff_command);
  auto args = reversed_arguments(data, size);
  try {
    app.parse(args);
  } catch (const CLI::ParseError&) {
    return 0;
  }
  if (audit->parsed()) apply_choices(audit_options);
  if (sniff->parsed()) apply_choices(sniff_command.options);
  return 0;
}
