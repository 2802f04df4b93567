#include "cli/glossary_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>

#include "cli/exit_status.h"
#include "formatting/json_writer.h"
#include "report/glossary.h"

namespace pvtap::analyzer {
namespace {

std::string as_text() {
  std::string o;
  for (const GlossaryTerm& t : glossary()) {
    o += t.term;
    o += "\n    ";
    o += t.meaning;
    if (!t.json_key.empty()) {
      o += "\n    jsonl summary: ";
      o += t.json_key;
    }
    o += '\n';
  }
  return o;
}

std::string as_jsonl() {
  std::string o;
  for (const GlossaryTerm& t : glossary()) {
    JsonWriter w(o);
    w.begin_object();
    w.field("term", t.term);
    w.key("key");
    if (t.json_key.empty()) {
      w.null();
    } else {
      w.string(t.json_key);
    }
    w.field("meaning", t.meaning);
    w.end_object();
    o += '\n';
  }
  return o;
}

// The README's glossary section is this output (a test holds them equal).
std::string as_markdown() {
  std::string o = "| term | meaning | jsonl summary key |\n|---|---|---|\n";
  for (const GlossaryTerm& t : glossary()) {
    o += "| ";
    o += t.term;
    o += " | ";
    o += t.meaning;
    o += " | ";
    if (!t.json_key.empty()) {
      o += '`';
      o += t.json_key;
      o += '`';
    }
    o += " |\n";
  }
  return o;
}

}  // namespace

CLI::App* add_glossary_command(CLI::App& app, GlossaryCommandLine& command) {
  CLI::App* glossary =
      app.add_subcommand("glossary",
                         "Print pvtap's words for what it finds (bad check, timeout, latency p95 "
                         "...), each with its one-line meaning and its key in the jsonl summary: "
                         "the words of the text report, the HTML page's tooltips and MQTT.");
  glossary->add_option("--format", command.format, "text, jsonl or markdown")
      ->check(CLI::IsMember({"text", "jsonl", "markdown"}).description(""))
      ->type_name("FORMAT")
      ->default_str("text");
  glossary->footer(
      "\nExamples:\n  pvtap glossary\n  pvtap glossary --format jsonl | jq -r "
      "'select(.term==\"timeout\").meaning'\n");
  return glossary;
}

int run_glossary(const GlossaryCommandLine& command) {
  const std::string out = command.format == "jsonl"      ? as_jsonl()
                          : command.format == "markdown" ? as_markdown()
                                                         : as_text();
  std::fwrite(out.data(), 1, out.size(), stdout);
  return kExitOk;
}

}  // namespace pvtap::analyzer
