#include "registration/record_layer.h"

#include <algorithm>

namespace pvtap::dissector {

InverterProtocol& protocol_of_record(tvbuff_t* tvb, packet_info* pinfo, RoleHint hint) {
  const guint n = std::min<guint>(tvb_captured_length(tvb), kMaxFrameLength);
  const auto* bytes = static_cast<const guint8*>(tvb_memdup(pinfo->pool, tvb, 0, n));
  const ProbeResult probe = probe_frame({bytes, n}, hint);
  if (probe.status == ProbeResult::Status::Complete) return protocol_of(probe.dialect);
  return rtu_protocol();
}

}  // namespace pvtap::dissector
