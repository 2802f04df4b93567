#include "formatting/csv_text.h"

namespace pvtap::analyzer {

void append_csv_field(std::string& out, std::string_view text) {
  // One pass to find a character that needs quoting, and plain runs copied at once.
  bool quoted = false;
  for (const char c : text) {
    if (c == ',' || c == '"' || c == '\r' || c == '\n') {
      quoted = true;
      break;
    }
  }
  if (!quoted) {
    out.append(text.data(), text.size());
    return;
  }
  out += '"';
  std::size_t run = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '"') continue;
    out.append(text.data() + run, i + 1 - run);  // up to and with the quote, which is doubled
    out += '"';
    run = i + 1;
  }
  out.append(text.data() + run, text.size() - run);
  out += '"';
}

}  // namespace pvtap::analyzer
