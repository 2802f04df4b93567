// Poll block addresses in the reference's notation.
#include "poll_block_text.h"

#include <cstdio>
#include <optional>

#include "pvtap/register_decoder.h"
#include "pvtap/register_map.h"

namespace pvtap::analyzer {

std::string block_start_text(const AuditSettings& settings, const PollBlock& b) {
  if (!b.start) return "-";
  const std::optional<std::uint16_t> written =
      written_address_of(b.dialect, *b.start, settings.gsl_ids);
  return std::string(written ? format_register_address(b.dialect, *written).view()
                             : format_register_address(Dialect::Hybrid, *b.start).view());
}

std::string block_text(const AuditSettings& settings, const PollBlock& b) {
  const std::string start = block_start_text(settings, b);
  const std::string count = b.count ? std::to_string(*b.count) : "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, "start %-6s count %-4s", start.c_str(), count.c_str());
  return buf;
}

}  // namespace pvtap::analyzer
