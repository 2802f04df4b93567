// The options `pvtap audit` and `pvtap sniff` share: protocol, register maps and output.
#pragma once

#include <cstdint>

#include "cli/command_options.h"
#include "pipeline/pipeline.h"
#include "run/run_output.h"

namespace CLI {
class App;
}

namespace pvtap {
class RegisterDecoder;
}

namespace pvtap::analyzer {

// The range --baud accepts, in audit and sniff alike: the rates an inverter bus runs at and
// `sniff --baud auto` tries (a tap sets the standard ones among them).
struct BaudRange {
  std::uint32_t min;
  std::uint32_t max;
};
inline constexpr BaudRange kBaudRange{1200, 115200};

// --dialect, --baud, --timeout, --gsl-ids, --map.
void add_protocol_options(CLI::App& command, CommonOptions& o, BaudRange baud_range);
// --format, --summary-only, --write, --fail-on.
void add_output_options(CLI::App& command, CommonOptions& o);
// --values, --values-format.
void add_values_options(CLI::App& command, CommonOptions& o);
// --html, --plot.
void add_html_options(CLI::App& command, CommonOptions& o);

// Turns the options as typed (dialect, format, ...) into their typed fields.
void apply_choices(CommonOptions& o);

// The exit status a finished run's findings give under --fail-on: kExitFindings or kExitOk.
int findings_status(const CommonOptions& o, const AuditReport& report);

// Loads the --map files into the decoder; false (after printing why) when one is bad.
bool load_maps(const CommonOptions& o, RegisterDecoder& decoder);

// What the options make of the pipeline and of the output.
PipelineSettings pipeline_settings(const CommonOptions& o);
OutputSettings output_settings(const CommonOptions& o);

}  // namespace pvtap::analyzer
