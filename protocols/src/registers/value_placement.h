// What each dialect's value rules share when they place a frame's words (private).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>

#include "pvtap/codec/frame.h"
#include "pvtap/registers/register_decoder.h"

namespace pvtap::detail {

// Whether `request` is the request of `reply`, with the start its words are placed at.
inline bool is_request_for(const Frame* request, const Frame& reply) {
  return request != nullptr && request->dialect == reply.dialect &&
         request->role == Role::Request && request->function == reply.function &&
         request->start.has_value();
}

// Notes in `report` whether the request could be used and whether its count fits.
inline void note_request_fit(DecodeReport& report, const Frame& reply, const Frame* request) {
  const bool usable = is_request_for(request, reply);
  report.request_unusable = request != nullptr && !usable;
  report.count_mismatch =
      usable && request->count.has_value() && *request->count != reply.words.size();
}

// A frame whose words are not placed (none, or without a known start).
inline DecodeReport nothing(ValueOrigin origin,
                            DecodeStatus status = DecodeStatus::NoRegisterData) {
  DecodeReport report;
  report.status = status;
  report.origin = origin;
  return report;
}

// The single word a write of one register carries.
inline std::span<const std::uint16_t> first_word(const Frame& frame) {
  return frame.words.span().first(std::min<std::size_t>(1, frame.words.size()));
}

}  // namespace pvtap::detail
