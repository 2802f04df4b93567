// The HTML report's polling: per bus, the poll blocks, the masters and the gaps in polling.
#include "html/html_sections.h"

#include <algorithm>
#include <cstdio>

#include "formatting/number_text.h"
#include "html/html_cells.h"
#include "html/html_text.h"
#include "report/frame_findings.h"
#include "report/poll_block_text.h"
#include "report/report_line.h"

namespace pvtap::analyzer {
namespace {

using namespace html_cells;

double longest_poll_period(const BusReport& bus) {
  double longest = 0;
  for (const PollPeriod& p : bus.timing.poll_periods) {
    if (p.period.intervals > 0) longest = std::max(longest, p.period.mean);
  }
  return longest;
}

void poll_table(std::string& o, const AuditReport& r, const BusReport& b) {
  o += "<table><tr>";
  term_heading(o, "station", "station");
  o += "<th>dialect</th><th>function</th><th>start</th><th>count</th><th>intervals</th>";
  term_heading(o, "period ms", "poll period");
  term_heading(o, "jitter ms", "jitter");
  o += "<th>max deviation ms</th></tr>\n";
  for (const PollPeriod& p : b.timing.poll_periods) {
    std::string function;
    append_function(function, p.block.dialect, p.block.function);
    o += "<tr>";
    cell(o, std::to_string(p.block.station));
    cell(o, to_string(p.block.dialect));
    cell(o, function);
    cell(o, block_start_text(r.settings, p.block));
    cell(o, p.block.count ? std::to_string(*p.block.count) : "-");
    count_cell(o, p.period.intervals);
    for (const double v : {p.period.mean, p.period.stddev, p.period.max_deviation}) {
      o += "<td class=\"n\">";
      o += p.period.intervals > 0 ? ms_text(v) : "-";
      o += "</td>";
    }
    o += "</tr>\n";
  }
  o += "</table>\n";
}

// The masters told apart by their poll cycles; two or more are a finding.
void masters_table(std::string& o, const AuditReport& r, const BusReport& b) {
  const std::vector<MasterPlan>& list = b.timing.masters;
  if (list.empty()) return;
  o += report_line("<h4>Masters: %zu</h4>\n", list.size());
  if (list.size() > 1) {
    o += report_line(
        "<p class=\"finding\">%zu masters on one bus: %zu independent poll cycles; "
        "%llu requests sent while another request's reply was due.</p>\n",
        list.size(), list.size(),
        static_cast<unsigned long long>(b.timing.requests_while_reply_due));
  }
  o += "<table><tr>";
  term_heading(o, "master", "master");
  o += "<th>cycle ms</th><th>requests</th><th>share %</th><th>turnaround ms</th>"
       "<th>poll plan</th></tr>\n";
  for (std::size_t i = 0; i < list.size(); ++i) {
    const MasterPlan& m = list[i];
    std::string plan;
    for (const std::size_t k : m.polls) {
      const PollBlock& block = b.timing.poll_periods[k].block;
      if (!plan.empty()) plan += "; ";
      plan += "st ";
      append_uint(plan, block.station);
      plan += ' ';
      append_function(plan, block.dialect, block.function);
      plan += ' ';
      plan += block_start_text(r.settings, block);
      if (block.count) {
        plan += " x";
        append_uint(plan, *block.count);
      }
    }
    o += "<tr>";
    cell(o, std::to_string(i + 1));
    cell(o, m.period > 0 ? ms_text(m.period) : "-");
    count_cell(o, m.requests);
    char share[16];
    std::snprintf(share, sizeof share, "%.1f", m.share * 100.0);
    cell(o, share);
    cell(o, m.turnaround ? ms_text(*m.turnaround) : "-");
    cell(o, plan);
    o += "</tr>\n";
  }
  o += "</table>\n";
}

void silence_list(std::string& o, const AuditReport& r, const BusFindings& bus, const Timeline& t) {
  std::string items;
  std::size_t n = 0;
  for (const PollSilence& s : t.silences) {
    if (s.bus != bus.name || !silence_is_finding(bus.report, s)) continue;
    ++n;
    items += "<li>";
    append_html_escaped(items, time_text(r, s.from) + " .. " + time_text(r, s.to));
    items += report_line(" (%.1f s)</li>", s.to - s.from);
  }
  o += report_line("<h4>Gaps in polling: %zu</h4>\n", n);
  o += "<p class=\"hint\">Stretches with no request longer than twice the longest poll period: "
       "the logger stopped asking.</p>\n";
  if (n > 0) o += "<ul class=\"silences\">" + items + "</ul>\n";
}

}  // namespace

bool silence_is_finding(const BusReport& bus, const PollSilence& s) {
  return s.to - s.from > std::max(Timeline::kMinSilence, 2 * longest_poll_period(bus));
}

void append_html_polling(std::string& o, const AuditReport& r, const Timeline& t) {
  o += "<section id=\"polling\"><h2>Polling</h2>\n";
  if (!r.settings.has_timestamps) {
    o += "<p>Not measured: the input has no timestamps.</p></section>\n";
    return;
  }
  for (const BusFindings& bus : r.buses) {
    o += "<h3>";
    append_html_escaped(o, bus_title(bus));
    o += "</h3>\n";
    poll_table(o, r, bus.report);
    masters_table(o, r, bus.report);
    silence_list(o, r, bus, t);
  }
  o += "</section>\n";
}

}  // namespace pvtap::analyzer
