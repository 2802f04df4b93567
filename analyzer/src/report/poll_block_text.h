// The registers of a poll block as the reference writes them, for every report rendering.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "pvtap/statistics/timing_statistics.h"
#include "report/audit_report.h"

namespace pvtap::analyzer {

// "start 1050   count 7   ": the start as the reference writes it (GSL IDs by the --gsl-ids
// reading; a wire address with no such ID in hex); "-" for a field the request does not have.
std::string block_text(const AuditSettings& settings, const PollBlock& b);
// The start alone ("1050", "0x1006", "-").
std::string block_start_text(const AuditSettings& settings, const PollBlock& b);
// The same for a start address on the wire of a dialect.
std::string start_address_text(const AuditSettings& settings, Dialect d,
                               std::optional<std::uint16_t> wire_start);

}  // namespace pvtap::analyzer
