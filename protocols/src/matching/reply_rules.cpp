#include "pvtap/matching/reply_rules.h"

#include "dialects/dialect_module.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap {
ReplyKind reply_kind(const FrameSummary& reply) {
  return detail::dialect_module(reply.dialect).reply_kind(reply.function);
}

bool same_dialect(Dialect a, Dialect b) {
  return detail::dialect_module(a).reply_family == detail::dialect_module(b).reply_family;
}

bool answers(const FrameSummary& request, const FrameSummary& reply) {
  // A gateway answers a request it could not forward with a Modbus exception.
  if (detail::dialect_module(request.dialect).answered_by_gateway_exception &&
      reply_kind(reply) == ReplyKind::GslException) {
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
  if (detail::dialect_module(reply.dialect).reply_repeats_start) {
    return reply.start == request.start;
  }
  return true;
}

bool reply_is_echo(Dialect d, std::uint8_t function) {
  return detail::dialect_module(d).reply_is_echo(function);
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
  return detail::dialect_module(request.dialect).compare_reply_count(request, reply);
}

}  // namespace pvtap
