#include "settings/register_decoding.h"

#include <optional>

#include "settings/register_maps.h"
#include "settings/station_maps.h"

namespace pvtap::dissector {
namespace {

std::optional<RegisterDecoder> g_decoder;

}  // namespace

void configure_register_decoder(DecoderOptions options) {
  RegisterDecoder decoder(options);
  // Field ids are keyed by the entries of the effective maps, so decode with exactly those.
  for (Dialect d : kAllDialects) decoder.use_map(d, effective_map(d));
  // A station's own map has no fields of its own: its values show in the generic map fields.
  use_station_maps(decoder);
  // Assigned in place: the bus sessions hold the decoder by reference.
  g_decoder = decoder;
}

const RegisterDecoder& register_decoder() {
  if (!g_decoder) configure_register_decoder({});
  return *g_decoder;
}

}  // namespace pvtap::dissector
