#include "pvtap/matching/reply_rules.h"

#include "pvtap/codec/function_codes.h"

namespace pvtap {
namespace {

std::optional<CountComparison> compare_hybrid(const FrameSummary& request,
                                              const FrameSummary& reply) {
  if (!reply.byte_count) return std::nullopt;
  const unsigned found = *reply.byte_count;
  if (fc::is_hybrid_read(request.function)) {
    if (!request.count) return std::nullopt;
    return CountComparison{4u + 2u * unsigned{*request.count}, found, CountUnit::Bytes};
  }
  // The seed's table fixes n = 8 for both; 4 + 2*count would wrongly flag every 0x1F reply.
  if (request.function == fc::kHybridWriteParameter ||
      request.function == fc::kHybridRestoreFactory) {
    return CountComparison{8u, found, CountUnit::Bytes};
  }
  return std::nullopt;
}

// GSL and plain Modbus: the reads whose reply carries a byte count the request fixes.
std::optional<CountComparison> compare_modbus(const FrameSummary& request,
                                              const FrameSummary& reply) {
  if (!request.count || !reply.byte_count) return std::nullopt;
  const unsigned qty = *request.count;
  const unsigned found = *reply.byte_count;
  switch (request.function) {
    case fc::kGslReadHolding:
    case fc::kGslReadInput:
    case fc::kReadWriteMultiple:
      return CountComparison{2u * qty, found, CountUnit::Bytes};
    case fc::kReadCoils:
    case fc::kReadDiscreteInputs:
      return CountComparison{(qty + 7u) / 8u, found, CountUnit::Bytes};
    default:
      return std::nullopt;
  }
}

// The functions whose normal reply repeats the request unchanged.
bool is_echoed(std::uint8_t f) {
  return f == fc::kGslWriteSingle || f == fc::kWriteSingleCoil || f == fc::kDiagnostics ||
         f == fc::kMaskWriteRegister || f == fc::kWriteFileRecord;
}

std::optional<CountComparison> compare_ascii(const FrameSummary& request,
                                             const FrameSummary& reply) {
  if (!request.count) return std::nullopt;
  return CountComparison{unsigned{*request.count}, unsigned{reply.word_count}, CountUnit::Words};
}

}  // namespace

ReplyKind reply_kind(const FrameSummary& reply) {
  if (reply.dialect == Dialect::Hybrid && reply.function == fc::kHybridError) {
    return ReplyKind::HybridError;
  }
  if (modbus_family(reply.dialect) && fc::is_gsl_exception(reply.function)) {
    return ReplyKind::GslException;
  }
  return ReplyKind::Normal;
}

bool same_dialect(Dialect a, Dialect b) {
  return a == b || (modbus_family(a) && modbus_family(b));
}

bool answers(const FrameSummary& request, const FrameSummary& reply) {
  // A gateway answers a Hybrid request it could not forward with a Modbus exception.
  if (request.dialect == Dialect::Hybrid && reply_kind(reply) == ReplyKind::GslException) {
    return (reply.function & ~fc::kExceptionFlag) == request.function;
  }
  if (!same_dialect(request.dialect, reply.dialect)) return false;
  switch (reply_kind(reply)) {
    case ReplyKind::HybridError:
      return true;
    case ReplyKind::GslException:
      return (reply.function & ~fc::kExceptionFlag) == request.function;
    case ReplyKind::Normal:
      break;
  }
  if (reply.function != request.function) return false;
  if (reply.dialect == Dialect::Ascii) return reply.start == request.start;
  return true;
}

bool reply_is_echo(Dialect d, std::uint8_t function) {
  return modbus_family(d) && is_echoed(function);
}

bool echoes_write(const FrameSummary& request, const FrameSummary& frame, bool frame_check_ok) {
  const auto is_write = [](const FrameSummary& f) { return reply_is_echo(f.dialect, f.function); };
  if (!is_write(request) || !is_write(frame) || request.station != frame.station ||
      request.function != frame.function) {
    return false;
  }
  if (!frame_check_ok) return true;
  return frame.start == request.start && frame.first_word == request.first_word &&
         frame.word_count == request.word_count && frame.byte_count == request.byte_count;
}

std::optional<CountComparison> compare_reply_count(const FrameSummary& request,
                                                   const FrameSummary& reply) {
  if (reply_kind(reply) != ReplyKind::Normal) return std::nullopt;
  switch (request.dialect) {
    case Dialect::Hybrid:
      return compare_hybrid(request, reply);
    case Dialect::Gsl:
    case Dialect::Modbus:
      return compare_modbus(request, reply);
    case Dialect::Ascii:
      return compare_ascii(request, reply);
  }
  return std::nullopt;
}

}  // namespace pvtap
