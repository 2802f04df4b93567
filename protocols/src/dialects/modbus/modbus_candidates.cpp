// Length rules of the public Modbus function codes (PROTOCOLS.md section 6) that GSL does
// not use; GSL's own codes are read by rtu_candidates.cpp.
#include "framing/candidate_reader.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap::detail {
namespace {

constexpr std::size_t kFixed = 8;    // addr fc word word crc
constexpr std::size_t kBare = 4;     // addr fc crc
constexpr std::size_t kCounted = 5;  // addr fc n ... crc, without the n bytes
constexpr unsigned kMaxBits = 2000;  // 0x01 0x02 quantity
constexpr unsigned kMaxWrittenBits = 1968;
constexpr unsigned kMaxReadRegisters = 125;
constexpr unsigned kMaxWrittenRegisters = 121;  // 0x17
constexpr unsigned kMaxFifoBytes = 2 + 2 * 31;
constexpr std::size_t kMaxAdu = 256;

bool in_range(unsigned v, unsigned lo, unsigned hi) {
  return v >= lo && v <= hi;
}

// The nine exception codes of the specification.
bool is_exception_code(std::uint8_t c) {
  return in_range(c, 1, 6) || c == 0x08 || c == 0x0A || c == 0x0B;
}

// Diagnostics: the sub-functions the serial line defines (0x00-0x04, 0x0A-0x12, 0x14).
void diagnostics(CandidateReader& r, Role role) {
  if (r.has(3)) {
    const unsigned sub = r.word(2);
    const bool known = in_range(sub, 0, 4) || in_range(sub, 0x0A, 0x12) || sub == 0x14;
    if (!known && r.reject_implausible()) return;
  }
  r.add(kFixed, role);
}

// addr fc n data[n] crc; `min_n` is the smallest byte count the function allows.
void counted(CandidateReader& r, Role role, unsigned min_n) {
  if (!r.has(2)) return;
  if (r.b[2] < min_n && r.reject_implausible()) return;
  r.add(kCounted + r.b[2], role);
}

void fixed_with_quantity(CandidateReader& r, Role role, unsigned max) {
  if (r.has(5) && !in_range(r.word(4), 1, max) && r.reject_implausible()) return;
  r.add(kFixed, role);
}

void write_single_coil(CandidateReader& r, Role role) {
  if (r.has(5) && r.word(4) != 0xFF00 && r.word(4) != 0x0000 && r.reject_implausible()) return;
  r.add(kFixed, role);
}

void write_multiple_coils_request(CandidateReader& r) {
  if (!r.has(6)) return;
  const unsigned qty = r.word(4);
  if ((!in_range(qty, 1, kMaxWrittenBits) || r.b[6] != (qty + 7) / 8) && r.reject_implausible()) {
    return;
  }
  r.add(9 + std::size_t{r.b[6]}, Role::Request);
}

void read_write_request(CandidateReader& r) {
  if (!r.has(10)) return;
  const unsigned read_qty = r.word(4);
  const unsigned write_qty = r.word(8);
  if ((!in_range(read_qty, 1, kMaxReadRegisters) || !in_range(write_qty, 1, kMaxWrittenRegisters) ||
       r.b[10] != 2 * write_qty) &&
      r.reject_implausible()) {
    return;
  }
  r.add(13 + std::size_t{r.b[10]}, Role::Request);
}

void device_identification_request(CandidateReader& r) {
  if (!r.has(3)) return;
  if (r.b[2] != fc::kMeiDeviceIdentification) return;  // other MEI types have no length rule
  if (!in_range(r.b[3], 1, 4) && r.reject_implausible()) return;
  r.add(7, Role::Request);
}

// MEI, code, conformity, more, next id, count, then `count` objects of (id, length, value).
void device_identification_reply(CandidateReader& r) {
  if (!r.has(2) || r.b[2] != fc::kMeiDeviceIdentification) return;
  if (!r.has(7)) return;
  if ((!in_range(r.b[3], 1, 4) || (r.b[5] != 0 && r.b[5] != 0xFF)) && r.reject_implausible()) {
    return;
  }
  std::size_t at = 8;
  for (unsigned object = 0; object < r.b[7]; ++object) {
    if (!r.has(at + 1)) return;
    at += 2 + std::size_t{r.b[at + 1]};
    if (at + 2 > kMaxAdu) return;
  }
  r.add(at + 2, Role::Response);
}

void fifo_reply(CandidateReader& r) {
  if (!r.has(3)) return;
  const unsigned n = r.word(2);
  if ((n < 2 || n > kMaxFifoBytes || n % 2 != 0) && r.reject_implausible()) return;
  r.add(6 + std::size_t{n}, Role::Response);
}

}  // namespace

void add_modbus_request(CandidateReader& r, std::uint8_t f) {
  switch (f) {
    case fc::kReadCoils:
    case fc::kReadDiscreteInputs:
      return fixed_with_quantity(r, Role::Request, kMaxBits);
    case fc::kWriteSingleCoil:
      return write_single_coil(r, Role::Request);
    case fc::kReadExceptionStatus:
    case fc::kCommEventCounter:
    case fc::kCommEventLog:
    case fc::kReportServerId:
      return r.add_unjudged(kBare, Role::Request);
    case fc::kDiagnostics:
      return diagnostics(r, Role::Request);  // one data word, as nearly every sub-function
    case fc::kWriteMultipleCoils:
      return write_multiple_coils_request(r);
    case fc::kReadFileRecord:
      return counted(r, Role::Request, 0x07);
    case fc::kWriteFileRecord:
      return counted(r, Role::Request, 0x09);
    case fc::kMaskWriteRegister:
      return r.add_unjudged(10, Role::Request);
    case fc::kReadWriteMultiple:
      return read_write_request(r);
    case fc::kReadFifoQueue:
      return r.add_unjudged(6, Role::Request);
    case fc::kEncapsulatedInterface:
      return device_identification_request(r);
    default:
      return;  // exceptions are never requests
  }
}

void add_modbus_response(CandidateReader& r, std::uint8_t f) {
  if (fc::is_gsl_exception(f)) {
    if (r.has(2) && !is_exception_code(r.b[2]) && r.reject_implausible()) return;
    return r.add(5, Role::Response);
  }
  switch (f) {
    case fc::kReadCoils:
    case fc::kReadDiscreteInputs:
    case fc::kReportServerId:
      return counted(r, Role::Response, 1);
    case fc::kCommEventLog:
      return counted(r, Role::Response, 6);
    case fc::kReadFileRecord:
    case fc::kWriteFileRecord:
      return counted(r, Role::Response, 2);
    case fc::kReadWriteMultiple:
      return counted(r, Role::Response, 2);
    case fc::kWriteSingleCoil:
      return write_single_coil(r, Role::Response);
    case fc::kWriteMultipleCoils:
      return fixed_with_quantity(r, Role::Response, kMaxWrittenBits);
    case fc::kReadExceptionStatus:
      return r.add_unjudged(5, Role::Response);
    case fc::kDiagnostics:
      return diagnostics(r, Role::Response);
    case fc::kCommEventCounter:
      return r.add_unjudged(kFixed, Role::Response);
    case fc::kMaskWriteRegister:
      return r.add_unjudged(10, Role::Response);
    case fc::kReadFifoQueue:
      return fifo_reply(r);
    case fc::kEncapsulatedInterface:
      return device_identification_reply(r);
    default:
      return;
  }
}

}  // namespace pvtap::detail
