// Typed frames of all dialects, independent of their wire encoding.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "pvtap/codec/dialect.h"

namespace pvtap {

// DeviceNumber: the Hybrid dialect's 4-byte device number (type code + 24-bit serial).
struct DeviceNumber {
  std::uint8_t type_code = 0;
  std::uint32_t serial = 0;  // 0 .. 0xFFFFFF
  bool operator==(const DeviceNumber&) const = default;
};

// WordList: data words of one frame, stored inline so that parsing never allocates.
class WordList {
 public:
  static constexpr std::size_t kCapacity = 256;  // ASCII count is one byte: at most 255 words

  WordList() = default;
  WordList(std::initializer_list<std::uint16_t> words) {
    for (auto w : words) push_back(w);
  }
  // A frame is copied a few times on its way (parsed, kept as a request): only the words in
  // use are, not the whole 512-byte array.
  WordList(const WordList& o) : size_(o.size_) {
    std::copy_n(o.words_.data(), size_, words_.data());
  }
  WordList& operator=(const WordList& o) {
    if (this != &o) {
      size_ = o.size_;
      std::copy_n(o.words_.data(), size_, words_.data());
    }
    return *this;
  }
  bool push_back(std::uint16_t w) {
    if (size_ == kCapacity) return false;
    words_[size_++] = w;
    return true;
  }
  void clear() { size_ = 0; }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  std::uint16_t operator[](std::size_t i) const { return words_[i]; }
  const std::uint16_t* begin() const { return words_.data(); }
  const std::uint16_t* end() const { return words_.data() + size_; }
  std::span<const std::uint16_t> span() const { return {words_.data(), size_}; }
  bool operator==(const WordList& o) const {
    return size_ == o.size_ && std::equal(begin(), end(), o.begin());
  }

 private:
  // Left unfilled: only the first size_ words are ever read, and zeroing 512 bytes for every
  // parsed frame showed in audit profiles.
  std::array<std::uint16_t, kCapacity> words_;
  std::size_t size_ = 0;
};

// ByteList: data bytes of one frame that are not registers (coil and input bits, file
// records, device identification objects), stored inline like WordList.
class ByteList {
 public:
  static constexpr std::size_t kCapacity = 256;  // a Modbus serial ADU is at most 256 bytes

  ByteList() = default;
  ByteList(std::initializer_list<std::uint8_t> bytes) {
    for (auto b : bytes) push_back(b);
  }
  ByteList(const ByteList& o) : size_(o.size_) {
    std::copy_n(o.bytes_.data(), size_, bytes_.data());
  }
  ByteList& operator=(const ByteList& o) {
    if (this != &o) {
      size_ = o.size_;
      std::copy_n(o.bytes_.data(), size_, bytes_.data());
    }
    return *this;
  }
  bool push_back(std::uint8_t b) {
    if (size_ == kCapacity) return false;
    bytes_[size_++] = b;
    return true;
  }
  bool assign(std::span<const std::uint8_t> bytes) {
    if (bytes.size() > kCapacity) return false;
    size_ = bytes.size();
    std::copy_n(bytes.data(), size_, bytes_.data());
    return true;
  }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  std::uint8_t operator[](std::size_t i) const { return bytes_[i]; }
  const std::uint8_t* begin() const { return bytes_.data(); }
  const std::uint8_t* end() const { return bytes_.data() + size_; }
  std::span<const std::uint8_t> span() const { return {bytes_.data(), size_}; }
  bool operator==(const ByteList& o) const {
    return size_ == o.size_ && std::equal(begin(), end(), o.begin());
  }

 private:
  std::array<std::uint8_t, kCapacity> bytes_;  // left unfilled, as WordList's words
  std::size_t size_ = 0;
};

// FrameHeader: the fields a frame and its summary for the matcher share.
struct FrameHeader {
  Dialect dialect = kDefaultDialect;
  Role role = Role::Request;
  std::uint8_t station = 0;
  std::uint8_t function = 0;  // as on the wire
  std::optional<std::uint16_t> start;
  std::optional<std::uint16_t> count;
  std::optional<std::uint8_t> byte_count;

  bool operator==(const FrameHeader&) const = default;
};

// Frame: one decoded frame. Which optional fields are set depends on the frame kind:
//
//   ASCII request          station, function 'R', start, count
//   ASCII reply            station, function 'R', start, words
//   Hybrid read request    start, count                        (0x11 0x12 0x16 0x17 0x1F)
//   Hybrid 0x18 request    start = register, words = {value}
//   Hybrid read reply      byte_count, device, words           (0x11 0x12 0x16 0x17)
//   Hybrid 0x18 reply      byte_count, device, start = register, words = {value}
//   Hybrid 0x1F/0xFF reply byte_count, device, start, count    (0xFF: start 0x1000, count 0x00FF)
//   GSL read request       start, count                        (0x03 0x04)
//   GSL read reply         byte_count, words
//   GSL 0x06 request/echo  start = register, words = {value}
//   GSL 0x10 request       start, count, byte_count, words
//   GSL 0x10 reply         start, count
//   GSL exception          function = fc|0x80, exception_code
//
// Plain Modbus frames (section 6) use the GSL forms for 0x03 0x04 0x06 0x10 and exceptions,
// and these:
//   0x01 0x02 request      start, count
//   0x01 0x02 reply        byte_count, data = the bits, bit 0 of byte 0 = start
//   0x05 request/echo      start = coil, words = {value}
//   0x07 reply             data = {status}                  (request: no fields)
//   0x08 request/echo      sub_function, words (or data when the data is an odd length)
//   0x0B reply             words = {status, event count}    (request: no fields)
//   0x0C 0x11 reply        byte_count, data                 (request: no fields)
//   0x0F request           start, count, byte_count, data
//   0x0F reply             start, count
//   0x14 0x15 both         byte_count, data = the sub-requests or records
//   0x16 request/echo      start = register, words = {and mask, or mask}
//   0x17 request           start, count (read), write_start, write_count, byte_count, words
//   0x17 reply             byte_count, words
//   0x18 request           start = FIFO pointer
//   0x18 reply             byte_count = FIFO byte count (2 bytes on the wire), count, words
//   0x2B request/reply     data = MEI type and what follows it
//
// A Hybrid 0x18/0x1F/0xFF reply whose byte count is not 8 keeps device + words instead.
struct Frame : FrameHeader {
  std::optional<DeviceNumber> device;
  std::optional<std::uint8_t> exception_code;
  std::optional<std::uint16_t> sub_function;
  std::optional<std::uint16_t> write_start;
  std::optional<std::uint16_t> write_count;
  WordList words;
  ByteList data;

  bool operator==(const Frame&) const = default;
};

// A frame with only its header fields set; the rest is filled in by the caller.
inline Frame make_frame(Dialect dialect, Role role, std::uint8_t station, std::uint8_t function) {
  Frame f;
  f.dialect = dialect;
  f.role = role;
  f.station = station;
  f.function = function;
  return f;
}

}  // namespace pvtap
