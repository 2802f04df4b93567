#include "pvtap/codec/frame_layout.h"

#include "dialects/dialect_module.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap {
namespace {

constexpr std::uint16_t kAsciiWordDigits = 4;

// Hands out consecutive byte ranges, in wire order, from the end of the header's function.
struct Cursor {
  explicit Cursor(const FrameLayout& header)
      : at(static_cast<std::uint16_t>(header.function.offset + header.function.length)) {}
  std::uint16_t at;
  FieldSpan take(std::size_t n) {
    const FieldSpan span{at, static_cast<std::uint16_t>(n)};
    at = static_cast<std::uint16_t>(at + n);
    return span;
  }
};

// The spans of a header of `size` bytes from `offset`, when the frame holds them.
FieldSpan within(std::size_t length, std::uint16_t offset, std::uint16_t size) {
  return length >= std::size_t{offset} + size ? FieldSpan{offset, size} : FieldSpan{};
}

FrameLayout ascii_header_layout(std::size_t length) {
  FrameLayout l;
  l.word_size = kAsciiWordDigits;
  l.start_delimiter = within(length, 0, 1);
  l.station = within(length, 1, 2);
  l.function = within(length, 3, 1);
  if (length >= 5) {
    l.check = {static_cast<std::uint16_t>(length - 5), 4};
    l.end_delimiter = {static_cast<std::uint16_t>(length - 1), 1};
  }
  return l;
}

FrameLayout rtu_header_layout(std::size_t length) {
  FrameLayout l;
  l.station = within(length, 0, 1);
  l.function = within(length, 1, 1);
  if (length >= 2) l.check = {static_cast<std::uint16_t>(length - 2), 2};
  return l;
}

FrameLayout ascii_layout(const Frame& f, std::size_t length) {
  FrameLayout l = ascii_header_layout(length);
  Cursor c(l);
  l.start = c.take(4);
  if (f.role == Role::Request) {
    l.count = c.take(2);
  } else {
    l.words = c.take(f.words.size() * kAsciiWordDigits);
  }
  return l;
}

// Reply with a byte count: addr fc n [device number] [start] [count] words crc.
void counted_reply_layout(const Frame& f, Cursor& c, FrameLayout& l) {
  l.byte_count = c.take(1);
  if (f.device) {
    l.device_type = c.take(1);
    l.device_serial = c.take(3);
  }
  if (f.start) l.start = c.take(2);
  if (f.count) l.count = c.take(2);
}

// Everything else: addr fc [start] [count] [n] words crc (GSL 0x10 requests carry n).
void plain_layout(const Frame& f, Cursor& c, FrameLayout& l) {
  if (f.exception_code) {
    l.exception_code = c.take(1);
    return;
  }
  if (f.start) l.start = c.take(2);
  if (f.count) l.count = c.take(2);
  if (f.byte_count) l.byte_count = c.take(1);
}

// The plain Modbus frames whose fields do not follow the order above: the diagnostics
// sub-function before its words, the 0x17 request's write start and quantity before its byte
// count, the 0x18 reply's two-byte byte count and FIFO count before its words.
void modbus_layout(const Frame& f, FrameLayout& l) {
  constexpr std::uint16_t kBody = 2;  // after station and function
  const auto words_from = [&](std::size_t offset) {
    return f.words.empty() ? FieldSpan{}
                           : FieldSpan{static_cast<std::uint16_t>(offset),
                                       static_cast<std::uint16_t>(f.words.size() * 2)};
  };
  switch (f.function) {
    case fc::kDiagnostics:
      l.words = words_from(kBody + 2);
      return;
    case fc::kReadWriteMultiple:
      if (f.role != Role::Request) return;
      l.byte_count = {kBody + 8, 1};
      l.words = words_from(kBody + 9);
      return;
    case fc::kReadFifoQueue:
      if (f.role != Role::Response) return;
      l.byte_count = {kBody, 2};
      l.count = {kBody + 2, 2};
      l.words = words_from(kBody + 4);
      return;
    default:
      return;
  }
}

FrameLayout rtu_layout(const Frame& f, std::size_t length) {
  FrameLayout l = rtu_header_layout(length);
  Cursor c(l);
  const bool counted_reply = f.role == Role::Response && (f.byte_count || f.device);
  if (counted_reply) {
    counted_reply_layout(f, c, l);
  } else {
    plain_layout(f, c, l);
  }
  if (!f.words.empty()) l.words = c.take(f.words.size() * 2);
  if (modbus_family(f.dialect) && !f.exception_code && l.check.present()) modbus_layout(f, l);
  return l;
}

}  // namespace

FieldSpan FrameLayout::word_span(std::size_t index, std::size_t n) const {
  const std::size_t size = word_size;
  const std::size_t words_in_frame = size == 0 ? 0 : std::size_t{words.length} / size;
  if (n == 0 || index >= words_in_frame || n > words_in_frame - index) return {};
  return {static_cast<std::uint16_t>(words.offset + index * size),
          static_cast<std::uint16_t>(n * size)};
}

FrameLayout header_layout(Dialect dialect, std::size_t length) {
  return detail::dialect_module(dialect).rtu_framed ? rtu_header_layout(length)
                                                    : ascii_header_layout(length);
}

FrameLayout frame_layout(const Frame& frame, std::size_t length) {
  return detail::dialect_module(frame.dialect).rtu_framed ? rtu_layout(frame, length)
                                                          : ascii_layout(frame, length);
}

}  // namespace pvtap
