#include "statistics/response_time_stats.h"

#include <epan/srt_table.h>
#include <epan/tap.h>

#include <string>

#include "pvtap/codec/function_codes.h"

namespace pvtap::dissector {
namespace {

constexpr int kFunctionCodes = 256;

// ResponseTimeSample: what the tap hands to the table: the request's function and time.
struct ResponseTimeSample {
  guint8 function;
  nstime_t request_time;
};

std::string row_name(Dialect d, std::uint8_t f) {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  std::string name = "0x";
  name += kDigits[f >> 4];
  name += kDigits[f & 0xF];
  name += ' ';
  name += fc::function_name(d, f);
  return name;
}

// The dialect that owns a function code in this protocol: a protocol of frames of their own
// holds one dialect.
Dialect dialect_of(const InverterProtocol& p, std::uint8_t f) {
  if (p.dialects.rtu()) return fc::rtu_dialect_of(f).value_or(kDefaultDialect);
  for (const Dialect d : kAllDialects) {
    if (p.dialects.contains(d)) return d;
  }
  return kDefaultDialect;
}

void init_table(register_srt_t* srt, GArray* srt_array) {
  const int proto = get_srt_proto_id(srt);
  const InverterProtocol& p = proto == ascii_protocol().proto ? ascii_protocol() : rtu_protocol();
  const std::string filter = std::string(p.filter_name) + ".function";
  srt_stat_table* table = init_srt_table(p.name, p.short_name, srt_array, kFunctionCodes,
                                         "Function", filter.c_str(), nullptr);
  for (int f = 0; f < kFunctionCodes; ++f) {
    const auto code = static_cast<std::uint8_t>(f);
    init_srt_table_row(table, f, row_name(dialect_of(p, code), code).c_str());
  }
}

tap_packet_status add_sample(void* tapdata, packet_info* pinfo, epan_dissect_t*, const void* data,
                             tap_flags_t) {
  const auto* sample = static_cast<const ResponseTimeSample*>(data);
  auto* srt = static_cast<srt_data_t*>(tapdata);
  if (sample == nullptr || srt == nullptr || srt->srt_array->len == 0) {
    return TAP_PACKET_DONT_REDRAW;
  }
  srt_stat_table* table = g_array_index(srt->srt_array, srt_stat_table*, 0);
  add_srt_table_data(table, sample->function, &sample->request_time, pinfo);
  return TAP_PACKET_REDRAW;
}

}  // namespace

void register_response_time_stats(InverterProtocol& p) {
  p.tap = register_tap(p.filter_name);
  register_srt_table(p.proto, nullptr, 1, add_sample, init_table, nullptr);
}

void queue_response_time(packet_info* pinfo, const InverterProtocol& p, const FrameRecord& reply) {
  if (reply.role != Role::Response || reply.request == nullptr || reply.duplicate ||
      reply.address_conflict)
    return;
  if (reply.request->packet == 0) return;  // not shown yet: no time to measure from
  auto* sample = wmem_new(pinfo->pool, ResponseTimeSample);
  sample->function = reply.request->function;
  sample->request_time.secs = static_cast<time_t>(reply.request->time.secs);
  sample->request_time.nsecs = reply.request->time.nsecs;
  tap_queue_packet(p.tap, pinfo, sample);
}

}  // namespace pvtap::dissector
