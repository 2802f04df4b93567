#include "settings/preferences.h"

#include <epan/prefs.h>

#include <string>

#include "settings/register_decoding.h"
#include "settings/station_maps.h"

namespace pvtap::dissector {
namespace {

const enum_val_t kGslIdReadings[] = {
    {"decimal", "Decimal", static_cast<gint>(GslIdReading::Decimal)},
    {"hex", "Hex", static_cast<gint>(GslIdReading::Hex)},
    {nullptr, nullptr, 0},
};

const enum_val_t kPairRules[] = {
    {"binary", "Binary", 0},
    {"decimal", "Decimal", 1},
    {nullptr, nullptr, 0},
};

void register_rtu_options(module_t* module, ProtocolSettings& s) {
  prefs_register_enum_preference(module, "gsl_ids", "GSL register IDs",
                                 "How the GSL seed's written register IDs go on the wire: "
                                 "decimal (ID 1050 is wire address 0x041A, the reference's "
                                 "reading) or hex (ID 1050 is wire address 0x1050)",
                                 &s.gsl_ids, kGslIdReadings, false);
  prefs_register_enum_preference(
      module, "pair_rule", "GSL 32-bit pairs",
      "How the two words of the GSL 32-bit values (total energy, CO2 reduction) combine: "
      "binary (high x 65536 + low) or decimal (high x 10000 + low)",
      &s.pair_rule, kPairRules, false);
  register_station_map_table(module);
}

}  // namespace

void register_preferences(InverterProtocol& p) {
  module_t* module = prefs_register_protocol(p.proto, apply_preferences);
  ProtocolSettings& s = p.settings;
  const std::string verify = std::string("verify_") + p.check_key;
  prefs_register_bool_preference(module, g_strdup(verify.c_str()),
                                 g_strdup((std::string("Verify the ") + p.check_word).c_str()),
                                 "Check every frame's integrity check and flag bad ones",
                                 &s.verify_check);
  prefs_register_bool_preference(module, "desegment", "Reassemble frames split over TCP segments",
                                 "Whether a frame cut by a segment end waits for the next "
                                 "segments (TCP preference \"Allow subdissector to reassemble "
                                 "TCP streams\" must be on too)",
                                 &s.desegment);
  prefs_register_uint_preference(module, "reply_timeout", "Reply timeout (ms)",
                                 "How long a request waits for its reply before it counts as "
                                 "unanswered",
                                 10, &s.reply_timeout_ms);
  prefs_register_uint_preference(module, "baud", "Bus baud rate",
                                 "Baud rate of the RS485 bus behind the gateway: how long the "
                                 "bytes of a segment took on the wire",
                                 10, &s.baud);
  prefs_register_uint_preference(
      module, "gateway_gap", "Gateway gap (ms)",
      "Silence between two segments of one direction that proves a frame boundary: a gateway "
      "packs bytes for a shorter time than this, so a longer pause was silence on the bus "
      "(0: segment times prove nothing). As pvtap audit's --gateway-gap.",
      10, &s.gateway_gap_ms);
  if (p.dialects.rtu()) register_rtu_options(module, s);
}

void apply_preferences() {
  const ProtocolSettings& s = rtu_protocol().settings;
  DecoderOptions options;
  options.gsl_ids =
      s.gsl_ids == static_cast<gint>(GslIdReading::Hex) ? GslIdReading::Hex : GslIdReading::Decimal;
  options.pair_rule = s.pair_rule == 1 ? PairRule::Decimal : PairRule::Binary;
  configure_register_decoder(options);
}

}  // namespace pvtap::dissector
