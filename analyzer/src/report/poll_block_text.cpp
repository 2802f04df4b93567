// Poll block addresses in the reference's notation.
#include "report/poll_block_text.h"

#include <cstdio>
#include <optional>

#include "pvtap/registers/register_decoder.h"
#include "pvtap/registers/register_map.h"

namespace pvtap::analyzer {

std::string start_address_text(const AuditSettings& settings, Dialect d,
                               std::optional<std::uint16_t> wire_start) {
  if (!wire_start) return "-";
  const std::optional<std::uint16_t> written = written_address_of(d, *wire_start, settings.gsl_ids);
  return std::string(written ? format_register_address(d, *written).view()
                             : format_wire_address(*wire_start).view());
}

std::string block_start_text(const AuditSettings& settings, const PollBlock& b) {
  return start_address_text(settings, b.dialect, b.start);
}

std::string block_text(const AuditSettings& settings, const PollBlock& b) {
  const std::string start = block_start_text(settings, b);
  const std::string count = b.count ? std::to_string(*b.count) : "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, "start %-6s count %-4s", start.c_str(), count.c_str());
  return buf;
}

}  // namespace pvtap::analyzer
