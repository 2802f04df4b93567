// Test helper: the few Frame shapes that many tests build by hand.
#pragma once

#include <cstdint>

#include "pvtap/codec/frame.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap::test {

// make_frame() taking the function as an int, as the tests write them (0x03, 'R').
inline Frame frame_of(Dialect d, Role r, std::uint8_t station, int function) {
  return make_frame(d, r, station, static_cast<std::uint8_t>(function));
}

// A read (or any start+count) request of an RTU or the ASCII dialect.
inline Frame read_request(Dialect d, std::uint8_t station, int function, std::uint16_t start,
                          std::uint16_t count) {
  Frame f = frame_of(d, Role::Request, station, function);
  f.start = start;
  f.count = count;
  return f;
}

inline Frame ascii_reply(std::uint8_t station, std::uint16_t start, WordList words) {
  Frame f = frame_of(Dialect::Ascii, Role::Response, station, fc::kAsciiRead);
  f.start = start;
  f.words = words;
  return f;
}

}  // namespace pvtap::test
