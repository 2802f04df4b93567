// The HTML report: one self-contained page (the charting library, script, style and data all
// inline) rendered from the same AuditReport as the text report, plus the Timeline of the run.
#pragma once

#include <string>
#include <vector>

#include "formatting/output_stream.h"
#include "html/timeline.h"
#include "report/audit_report.h"

namespace pvtap::analyzer {

// HtmlOptions: what narrows the page.
struct HtmlOptions {
  std::vector<std::string> plot_keys;  // register keys to chart; empty: every one that changed
};

void write_html_report(const AuditReport& report, const Timeline& timeline,
                       const HtmlOptions& options, OutputStream& out);

}  // namespace pvtap::analyzer
