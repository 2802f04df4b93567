#include "pvtap/registers/coil_bits.h"

#include <algorithm>
#include <array>

#include "pvtap/codec/function_codes.h"

namespace pvtap {
namespace {

constexpr std::array<std::uint8_t, 1> kOn{0x01};
constexpr std::array<std::uint8_t, 1> kOff{0x00};

std::uint16_t held(std::size_t bytes, std::uint16_t wanted) {
  return static_cast<std::uint16_t>(std::min<std::size_t>(wanted, bytes * 8));
}

std::optional<CoilBits> read_reply(const Frame& f, const Frame* request) {
  CoilBits out;
  out.inputs = f.function == fc::kReadDiscreteInputs;
  out.bytes = f.data.span();
  const bool placed = request != nullptr && request->function == f.function &&
                      request->role == Role::Request && request->start && request->count;
  if (placed) {
    out.start = request->start;
    out.count = held(out.bytes.size(), *request->count);
  } else {
    out.count = held(out.bytes.size(), 0xFFFF);
  }
  return out;
}

std::optional<CoilBits> single_write(const Frame& f) {
  if (!f.start || f.words.size() != 1) return std::nullopt;
  const std::uint16_t value = f.words[0];
  if (value != 0xFF00 && value != 0x0000) return std::nullopt;
  CoilBits out;
  out.start = f.start;
  out.count = 1;
  out.bytes = value == 0xFF00 ? std::span<const std::uint8_t>(kOn) : kOff;
  return out;
}

}  // namespace

std::optional<CoilBits> coil_bits(const Frame& f, const Frame* request) {
  if (!modbus_family(f.dialect)) return std::nullopt;
  switch (f.function) {
    case fc::kReadCoils:
    case fc::kReadDiscreteInputs:
      if (f.role != Role::Response) return std::nullopt;
      return read_reply(f, request);
    case fc::kWriteSingleCoil:
      return single_write(f);
    case fc::kWriteMultipleCoils: {
      if (f.role != Role::Request || !f.start || !f.count) return std::nullopt;
      CoilBits out;
      out.start = f.start;
      out.bytes = f.data.span();
      out.count = held(out.bytes.size(), *f.count);
      return out;
    }
    default:
      return std::nullopt;
  }
}

std::optional<std::uint16_t> CoilBits::address(std::size_t i) const {
  if (!start || *start + i > 0xFFFF) return std::nullopt;
  return static_cast<std::uint16_t>(*start + i);
}

const CoilDef* coil_def(const RegisterMap& map, const CoilBits& bits, std::size_t i) {
  const std::optional<std::uint16_t> at = bits.address(i);
  if (!at) return nullptr;
  return bits.inputs ? map.find_discrete_input(*at) : map.find_coil(*at);
}

}  // namespace pvtap
