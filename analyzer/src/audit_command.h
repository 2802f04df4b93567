// The `audit` subcommand: its command-line interface and what running it means.
#pragma once

#include "audit_options.h"

namespace CLI {
class App;
}

namespace pvtap::analyzer {

// Adds `audit` to the program's command line; parsed values land in `options`.
CLI::App* add_audit_command(CLI::App& app, AuditOptions& options);

// Runs an audit after parsing: checks inputs and maps, then reads. Returns the exit status.
int run_audit(AuditOptions& options);

}  // namespace pvtap::analyzer
