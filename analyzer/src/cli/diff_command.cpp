#include "cli/diff_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "cli/audit_input.h"
#include "cli/common_options.h"
#include "cli/exit_status.h"
#include "diff/diff_writers.h"
#include "diff/register_ranges.h"
#include "events/event_fanout.h"
#include "formatting/output_stream.h"

namespace pvtap::analyzer {
namespace {

const char* const kDescription =
    "Compare the bus before and after a change (a new terminator, a re-addressed meter, a "
    "logger firmware update): per bus and station, what changed beyond the noise of sampling.";

const char* const kFooter =
    "\nSides: BEFORE and AFTER are each one capture, or several files of one capture given\n"
    "comma-separated (ring.pcap,ring1.pcap), of any input kind pvtap audit reads (see pvtap\n"
    "audit --help): gateway captures, serial captures, pvtap's own link type 252, logic\n"
    "recordings, or with --raw plain dumps of bus bytes. Both sides are read with the same\n"
    "--dialect, --baud, --timeout, --gateway-gap, --gsl-ids, --map, --port, --channels, --de,\n"
    "--samplerate and --threads, as pvtap audit reads them. Buses pair by name; a side with\n"
    "one bus pairs it with the other side's one bus whatever their names.\n"
    "\nWhat is compared, per bus: noise bytes per 1000 bytes, bad checks of no station per\n"
    "1000 frames; per station: whether it appeared or vanished, requests per minute, bad\n"
    "checks per 1000 frames, timeouts and exceptions per 1000 requests, latency p50 and p95\n"
    "(where each side measured 10 or more), the poll blocks the master polls (newly polled,\n"
    "no longer polled), each block's poll period and jitter, and the registers read on both\n"
    "sides whose after-range leaves their before-range.\n"
    "\nNoise of sampling: rates are compared, not counts, so captures of different lengths\n"
    "compare. A rate differs when its change exceeds --rate-change (per 1000; for requests per\n"
    "minute only the percentage) and --rate-percent (--requests-percent) of the before rate,\n"
    "and lies beyond --noise-sigmas standard deviations of Poisson noise: with k1 of n1 before\n"
    "and k2 of n2 after, |k2/n2 - k1/n1| > sigmas * sqrt(p * (1/n1 + 1/n2)), p = (k1+k2) /\n"
    "(n1+n2). A latency, period or jitter differs when its change exceeds both its ms and its\n"
    "percent threshold. A register moved when its after-range leaves its before-range by more\n"
    "than --value-percent of the before-range's size (or magnitude, if larger); moves are\n"
    "reported but do not count toward the exit status unless --count-values.\n"
    "\nOutput on stdout: text (per bus, per station, before -> after and why), or jsonl: one\n"
    "{\"type\":\"difference\",...} line each, then a {\"type\":\"summary\",...} line. --html FILE\n"
    "also writes the differences as one self-contained page.\n"
    "\nExit status (as diff(1)): 0 no difference beyond the noise of sampling; 1 differences;\n"
    "2 usage error, an input unreadable or damaged, or a side with no frame.\n"
    "\nExamples:\n"
    "  pvtap diff before.pcap after.pcap\n"
    "  pvtap diff --format jsonl monday.pcap tuesday.pcap | jq 'select(.station==3)'\n"
    "  pvtap diff --port 4001 --html change.html old.pcap,old1.pcap new.pcap\n"
    "  pvtap diff --raw --dialect gsl --baud 4800 before.bin after.bin\n";

// Each default shown in --help is the DiffThresholds default itself.
void add_threshold_options(CLI::App& diff, DiffThresholds& t) {
  diff.add_option("--noise-sigmas", t.noise_sigmas,
                  "a rate's change must lie beyond this many standard deviations of Poisson "
                  "noise")
      ->check(CLI::Range(0.0, 100.0).description(""))
      ->type_name("N")
      ->capture_default_str();
  diff.add_option("--rate-change", t.rate_per_1000,
                  "least change of a rate per 1000 (bad checks per 1000 frames, timeouts and "
                  "exceptions per 1000 requests, noise bytes per 1000 bytes)")
      ->check(CLI::Range(0.0, 1000.0).description(""))
      ->type_name("PER_1000")
      ->capture_default_str();
  diff.add_option("--rate-percent", t.rate_percent,
                  "least change of those rates, in percent of the before rate")
      ->check(CLI::Range(0.0, 1e6).description(""))
      ->type_name("PERCENT")
      ->capture_default_str();
  diff.add_option("--requests-percent", t.requests_percent,
                  "least change of a station's requests per minute, in percent")
      ->check(CLI::Range(0.0, 1e6).description(""))
      ->type_name("PERCENT")
      ->capture_default_str();
  diff.add_option("--latency-ms", t.latency_ms, "least change of latency p50 or p95, in ms")
      ->check(CLI::Range(0.0, 1e6).description(""))
      ->type_name("MS")
      ->capture_default_str();
  diff.add_option("--latency-percent", t.latency_percent,
                  "least change of latency p50 or p95, in percent")
      ->check(CLI::Range(0.0, 1e6).description(""))
      ->type_name("PERCENT")
      ->capture_default_str();
  diff.add_option("--period-ms", t.period_ms, "least change of a poll period, in ms")
      ->check(CLI::Range(0.0, 1e7).description(""))
      ->type_name("MS")
      ->capture_default_str();
  diff.add_option("--period-percent", t.period_percent, "least change of a poll period, in percent")
      ->check(CLI::Range(0.0, 1e6).description(""))
      ->type_name("PERCENT")
      ->capture_default_str();
  diff.add_option("--jitter-ms", t.jitter_ms, "least change of a poll block's jitter, in ms")
      ->check(CLI::Range(0.0, 1e7).description(""))
      ->type_name("MS")
      ->capture_default_str();
  diff.add_option("--jitter-percent", t.jitter_percent,
                  "least change of a poll block's jitter, in percent")
      ->check(CLI::Range(0.0, 1e6).description(""))
      ->type_name("PERCENT")
      ->capture_default_str();
  diff.add_option("--value-percent", t.value_percent,
                  "how far a register's after-range may leave its before-range, in percent "
                  "of the before-range's size or magnitude")
      ->check(CLI::Range(0.0, 1e6).description(""))
      ->type_name("PERCENT")
      ->capture_default_str();
  diff.add_flag("--count-values", t.count_values,
                "register range moves count toward the exit status (without it they are "
                "reported only)");
}

// "a.pcap,b.pcap" as its files.
std::vector<std::string> side_files(const std::string& side) {
  std::vector<std::string> files;
  std::size_t begin = 0;
  while (begin <= side.size()) {
    const std::size_t comma = side.find(',', begin);
    const std::size_t end = comma == std::string::npos ? side.size() : comma;
    if (end > begin) files.push_back(side.substr(begin, end - begin));
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  return files;
}

// Audits one side into `side`; false after a `pvtap:` line when it cannot be read whole or
// holds no frame.
bool read_side(const DiffCommandLine& command, const std::string& given,
               const RegisterDecoder& decoder, DiffSide& side) {
  AuditOptions options = command.reading;
  (command.raw ? options.raw_dumps : options.captures) = side_files(given);
  if (options.raw_dumps.empty() && options.captures.empty()) {
    std::fprintf(stderr, "pvtap: diff: a side names no file: '%s'\n", given.c_str());
    return false;
  }
  AuditInput input(options);
  if (!input.plan()) return false;
  PipelineSettings settings = input.pipeline_settings(pipeline_settings(options));
  settings.decode_values = true;  // for the registers' ranges
  RegisterRanges ranges;
  EventFanout events;
  events.add(ranges);
  Pipeline pipeline(settings, decoder, events);
  const bool complete = input.read(pipeline);
  side.report = pipeline.report();
  input.complete(side.report);
  if (!complete) {
    input.report_problems();
    std::fprintf(stderr, "pvtap: %s: not read whole, so nothing is compared\n", given.c_str());
    return false;
  }
  if (found_no_frame(side.report)) {
    std::fprintf(stderr, "pvtap: %s: no frame found, nothing to compare\n", given.c_str());
    return false;
  }
  side.ranges = ranges.ranges();
  return true;
}

bool write_html(const std::string& path, const DiffReport& report) {
  std::string page;
  append_diff_html(page, report);
  std::FILE* file = std::fopen(path.c_str(), "wb");
  bool ok = file != nullptr && std::fwrite(page.data(), 1, page.size(), file) == page.size();
  if (file != nullptr) ok = std::fclose(file) == 0 && ok;
  if (!ok) std::fprintf(stderr, "pvtap: %s: cannot write the HTML page\n", path.c_str());
  return ok;
}

}  // namespace

CLI::App* add_diff_command(CLI::App& app, DiffCommandLine& command) {
  CLI::App* diff = app.add_subcommand("diff", kDescription);
  diff->footer(kFooter);
  diff->add_option("BEFORE", command.before,
                   "the capture before the change (several files: comma-separated)")
      ->type_name("FILE[,FILE]")
      ->required();
  diff->add_option("AFTER", command.after,
                   "the capture after the change (several files: comma-separated)")
      ->type_name("FILE[,FILE]")
      ->required();
  diff->add_flag("--raw", command.raw, "both sides are plain dumps of bus bytes (no timestamps)");
  add_reading_options(*diff, command.reading);
  add_protocol_options(*diff, command.reading, kBaudRange);
  diff->add_option("--format", command.format, "output format: text or jsonl")
      ->check(CLI::IsMember({"text", "jsonl"}).description(""))
      ->type_name("FORMAT")
      ->default_str("text");
  diff->add_option("--html", command.html_path,
                   "also write the differences as one self-contained HTML page to FILE")
      ->type_name("FILE");
  add_threshold_options(*diff, command.thresholds);
  return diff;
}

int run_diff(DiffCommandLine& command) {
  apply_choices(command.reading);
  if (command.reading.threads == 0) command.reading.threads = default_threads();
  RegisterDecoder decoder(
      DecoderOptions{command.reading.gsl_ids, PairRule::Binary, !command.reading.no_sunspec});
  if (!load_maps(command.reading, decoder)) return kExitBadInput;
  DiffSide before;
  DiffSide after;
  if (!read_side(command, command.before, decoder, before) ||
      !read_side(command, command.after, decoder, after)) {
    return kExitBadInput;
  }
  DiffReport report;
  report.before_label = command.before;
  report.after_label = command.after;
  report.before = &before;
  report.after = &after;
  report.thresholds = command.thresholds;
  report.result = compare_sides(before, after, command.thresholds);
  OutputStream out(stdout);
  if (command.format == "jsonl") {
    append_diff_jsonl(out.buffer(), report);
  } else {
    append_diff_text(out.buffer(), report);
  }
  out.flush();
  if (out.failed()) {
    std::fprintf(stderr, "pvtap: cannot write the output\n");
    return kExitBadInput;
  }
  if (!command.html_path.empty() && !write_html(command.html_path, report)) return kExitBadInput;
  return report.result.counted() > 0 ? kExitFindings : kExitOk;
}

}  // namespace pvtap::analyzer
