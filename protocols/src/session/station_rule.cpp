#include "pvtap/session/station_rule.h"

namespace pvtap {

std::optional<std::uint8_t> transaction_station(const Transaction& t) {
  // Pairing is by station (see TransactionMatcher), so a good reply to a damaged request
  // carries the station the request claimed; only two damaged frames leave it unknown.
  const bool named = t.broadcast ? t.reply_check_ok : t.request_check_ok || t.reply_check_ok;
  if (!named) return std::nullopt;
  return t.station;
}

std::optional<std::uint8_t> frame_station(bool check_ok, std::uint8_t address,
                                          const FrameMatch& match) {
  if (check_ok) return address;
  if (match.transaction) return transaction_station(*match.transaction);
  return std::nullopt;
}

std::optional<std::uint8_t> answered_request_station(const Transaction& t) {
  if (t.broadcast) return std::nullopt;
  return transaction_station(t);
}

std::optional<std::uint8_t> unanswered_station(const Timeout& t) {
  if (!t.request_check_ok) return std::nullopt;
  return t.station;
}

}  // namespace pvtap
