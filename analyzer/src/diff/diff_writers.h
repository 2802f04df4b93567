// `pvtap diff`'s differences written out: text for an operator, jsonl for jq, and an HTML page.
// All three write the same differences in the same order (per bus, per station).
#pragma once

#include <string>
#include <string_view>

#include "diff/capture_diff.h"

namespace pvtap::analyzer {

// DiffReport: what the writers show: the sides as given, what they held, the thresholds and
// the differences.
struct DiffReport {
  std::string before_label;  // the side's files as given, comma-separated
  std::string after_label;
  const DiffSide* before = nullptr;
  const DiffSide* after = nullptr;
  DiffThresholds thresholds;
  DiffResult result;
};

// The words for a difference's key ("bad checks per 1000 frames" for
// "bad_checks_per_1000_frames"); the key itself where it has none.
std::string_view difference_words(std::string_view what);

// Text: a line per side, then per bus and station each difference with before -> after and
// why, then one line that counts them (or says there are none).
void append_diff_text(std::string& out, const DiffReport& report);
// jsonl: {"type":"difference",...} per difference, then {"type":"summary",...}.
void append_diff_jsonl(std::string& out, const DiffReport& report);
// A self-contained HTML page (the audit report's style) with a table per bus.
void append_diff_html(std::string& out, const DiffReport& report);

}  // namespace pvtap::analyzer
