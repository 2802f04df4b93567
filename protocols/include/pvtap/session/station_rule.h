// Station rule: which station a frame or a finding is counted under, and why a station exists.
//
// A station exists because a frame whose check holds names it. A damaged frame's station byte
// may be the damaged byte, so it names no station: it belongs to the station of the good frame
// it is paired with (a damaged reply to its request's, a damaged request to its reply's), and
// otherwise to the unknown station, which keeps the address it claimed. Every per-station
// table reads this rule, through SessionFrame::station and SessionTimeout::station.
#pragma once

#include <cstdint>
#include <optional>

#include "pvtap/matching/match_events.h"

namespace pvtap {

// The station of a transaction: the one its request or its reply names with a good check; a
// broadcast's only by its reply (the request names every station). nullopt when neither does.
std::optional<std::uint8_t> transaction_station(const Transaction& t);

// The station of a frame as it is handled: its own address when its check holds; for a damaged
// reply, the station of the transaction it completes. nullopt for any other damaged frame (a
// damaged request is settled later, by the transaction its reply completes or its timeout).
std::optional<std::uint8_t> frame_station(bool check_ok, std::uint8_t address,
                                          const FrameMatch& match);

// The station of a damaged request that a reply answered: the transaction's, except for a
// broadcast, whose request names every station and so is no one station's.
std::optional<std::uint8_t> answered_request_station(const Transaction& t);

// The station of a request given up without a reply: its own address when its check held.
std::optional<std::uint8_t> unanswered_station(const Timeout& t);

}  // namespace pvtap
