#include "pvtap/matching/request_rules.h"

#include "pvtap/codec/function_codes.h"

namespace pvtap {
namespace {

std::optional<QuantityProblem> outside(unsigned found, unsigned max, bool write_part) {
  if (found >= 1 && found <= max) return std::nullopt;
  return QuantityProblem{found, 1, max, write_part};
}

}  // namespace

std::optional<WriteCountProblem> write_count_problem(const Frame& request) {
  if (!modbus_family(request.dialect) || request.role != Role::Request || !request.byte_count) {
    return std::nullopt;
  }
  std::optional<unsigned> quantity;
  unsigned expected = 0;
  switch (request.function) {
    case fc::kWriteMultipleCoils:
      quantity = request.count;
      if (quantity) expected = (*quantity + 7) / 8;
      break;
    case fc::kGslWriteMultiple:
      quantity = request.count;
      if (quantity) expected = 2 * *quantity;
      break;
    case fc::kReadWriteMultiple:
      quantity = request.write_count;
      if (quantity) expected = 2 * *quantity;
      break;
    default:
      return std::nullopt;
  }
  if (!quantity || *request.byte_count == expected) return std::nullopt;
  return WriteCountProblem{*request.byte_count, *quantity, expected};
}

bool may_broadcast(std::uint8_t function) {
  switch (function) {
    case fc::kWriteSingleCoil:
    case fc::kGslWriteSingle:
    case fc::kDiagnostics:  // force listen only mode is broadcast too
    case fc::kWriteMultipleCoils:
    case fc::kGslWriteMultiple:
    case fc::kWriteFileRecord:
    case fc::kMaskWriteRegister:
      return true;
    default:
      return false;
  }
}

bool broadcast_not_allowed(const FrameHeader& request, bool check_ok) {
  return check_ok && modbus_family(request.dialect) && request.role == Role::Request &&
         request.station == fc::kModbusBroadcast && !may_broadcast(request.function);
}

std::optional<unsigned> max_quantity(std::uint8_t f) {
  switch (f) {
    case fc::kReadCoils:
    case fc::kReadDiscreteInputs:
      return 2000;
    case fc::kGslReadHolding:
    case fc::kGslReadInput:
    case fc::kReadWriteMultiple:
      return 125;
    case fc::kWriteMultipleCoils:
      return 1968;
    case fc::kGslWriteMultiple:
      return 123;
    default:
      return std::nullopt;
  }
}

std::optional<QuantityProblem> quantity_problem(const Frame& request) {
  if (!modbus_family(request.dialect) || request.role != Role::Request || !request.count) {
    return std::nullopt;
  }
  const auto max = max_quantity(request.function);
  if (!max) return std::nullopt;
  if (auto read = outside(*request.count, *max, false)) return read;
  if (request.function == fc::kReadWriteMultiple && request.write_count) {
    return outside(*request.write_count, 121, true);
  }
  return std::nullopt;
}

}  // namespace pvtap
