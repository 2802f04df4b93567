// The scripts and styles inlined into every HTML report, embedded at build time
// (analyzer/CMakeLists.txt): dygraphs and its synchronizer from Debian's libjs-dygraphs, and
// the page's own script and style from report/assets/.
#pragma once

#include <string_view>

namespace pvtap::analyzer::html_assets {

extern const std::string_view dygraph_js;
extern const std::string_view dygraph_sync_js;
extern const std::string_view dygraph_css;
extern const std::string_view page_js;
extern const std::string_view page_css;

}  // namespace pvtap::analyzer::html_assets
