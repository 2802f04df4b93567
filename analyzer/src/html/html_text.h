// Text into HTML: escaping for element content and attribute values, and JSON inside a
// <script> element (where "</" must not appear).
#pragma once

#include <string>
#include <string_view>

namespace pvtap::analyzer {

// Escapes &, <, >, " and ' so that `text` reads as itself in content and quoted attributes.
void append_html_escaped(std::string& out, std::string_view text);

// Makes JSON safe inside <script type="application/json">: every "<" becomes "\u003c", which
// JSON.parse reads back as "<" (inside strings, the only place JSON has one).
void append_script_safe_json(std::string& out, std::string_view json);

}  // namespace pvtap::analyzer
