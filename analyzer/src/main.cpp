// pvtap: tools for the serial protocols of solar inverters on RS485 buses.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "cli/audit_command.h"
#include "cli/diff_command.h"
#include "cli/exit_status.h"
#include "cli/glossary_command.h"
#include "cli/help_labels.h"
#include "cli/sniff_command.h"
#include "cli/version_text.h"
#include "extcap/extcap_command.h"

namespace {

// What the build knows of its plugin (dissector/CMakeLists.txt defines these when it builds one).
pvtap::analyzer::PluginBuild plugin_build() {
#ifdef PVTAP_PLUGIN_SERIES
  return {PVTAP_PLUGIN_SERIES, PVTAP_PLUGIN_BUILD_PATH, PVTAP_PLUGIN_INSTALL_PATH};
#else
  return {};
#endif
}

}  // namespace

int main(int argc, char** argv) {
  // Wireshark runs capture interfaces as `pvtap --extcap-interfaces`, `--capture ...`.
  if (pvtap::analyzer::is_extcap_call(argc, argv)) return pvtap::analyzer::run_extcap(argc, argv);
  CLI::App app{"pvtap: see what crosses the wire between a data logger and its inverters", "pvtap"};
  app.require_subcommand(1);
  app.set_version_flag(
      "--version", [] { return pvtap::analyzer::version_text(plugin_build()); },
      "print the version and where the Wireshark plugin is, and exit");
  pvtap::analyzer::AuditOptions audit_options;
  CLI::App* audit = pvtap::analyzer::add_audit_command(app, audit_options);
  pvtap::analyzer::SniffCommandLine sniff_command;
  CLI::App* sniff = pvtap::analyzer::add_sniff_command(app, sniff_command);
  pvtap::analyzer::DiffCommandLine diff_command;
  CLI::App* diff = pvtap::analyzer::add_diff_command(app, diff_command);
  pvtap::analyzer::GlossaryCommandLine glossary_command;
  CLI::App* glossary = pvtap::analyzer::add_glossary_command(app, glossary_command);
  pvtap::analyzer::keep_help_section_names(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // Help is a success; every other parse problem is a usage error (exit 2), said on one
    // line by pvtap with where the valid forms are listed.
    if (e.get_exit_code() == 0) return app.exit(e);
    const char* command = audit->parsed()      ? "audit "
                          : sniff->parsed()    ? "sniff "
                          : diff->parsed()     ? "diff "
                          : glossary->parsed() ? "glossary "
                                               : "";
    std::fprintf(stderr, "pvtap: %s (see pvtap %s--help)\n", e.what(), command);
    return pvtap::analyzer::kExitBadInput;
  }
  if (audit->parsed()) return pvtap::analyzer::run_audit(audit_options);
  if (sniff->parsed()) return pvtap::analyzer::run_sniff(sniff_command);
  if (diff->parsed()) return pvtap::analyzer::run_diff(diff_command);
  if (glossary->parsed()) return pvtap::analyzer::run_glossary(glossary_command);
  return pvtap::analyzer::kExitBadInput;
}
