// The `audit` subcommand: its command-line interface and what running it means.
#pragma once

#include "cli/command_options.h"
#include "formatting/output_stream.h"

namespace CLI {
class App;
}

namespace pvtap::analyzer {

// Adds `audit` to the program's command line; parsed values land in `options`.
CLI::App* add_audit_command(CLI::App& app, AuditOptions& options);

// Runs an audit after parsing: checks inputs and maps, then reads. Returns the exit status.
int run_audit(AuditOptions& options);

// The audit itself, on maps already loaded: the inputs checked (AuditInput) and read into a
// pipeline, its events and the report to `out`. Returns the exit status.
int audit(const AuditOptions& options, const RegisterDecoder& decoder, OutputStream& out);

}  // namespace pvtap::analyzer
