// Glossary: pvtap's words for what it finds, each with its one-line meaning and its jsonl key,
// the one vocabulary of the text report, the HTML page, jsonl and MQTT.
#pragma once

#include <span>
#include <string_view>

namespace pvtap::analyzer {

struct GlossaryTerm {
  std::string_view term;      // as the reports write it: "bad check", "latency p95"
  std::string_view json_key;  // its key in the jsonl summary ("buses[].polls[].jitter_ms"),
                              // empty when it names no number of its own
  std::string_view meaning;   // one line, for tooltips, --help-like lists and the README
};

// Every term, in the order a reader meets them in the report.
std::span<const GlossaryTerm> glossary();

// The term named `term`; nullptr when the glossary has none (a writer's word that is not a
// term: a test holds every writer's headings to this).
const GlossaryTerm* glossary_term(std::string_view term);

// The term whose number the jsonl summary keeps under `json_key`; nullptr when none.
const GlossaryTerm* glossary_term_of_key(std::string_view json_key);

// The meaning of `term`, empty when it is no term.
std::string_view meaning_of(std::string_view term);

}  // namespace pvtap::analyzer
