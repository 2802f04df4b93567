// The register decoder both protocols share: the effective maps, the stations' own maps and the
// preferred options.
#pragma once

#include "pvtap/registers/register_decoder.h"

namespace pvtap::dissector {

// Rebuilds the decoder; called at registration and whenever the preferences or the station
// register maps change.
void configure_register_decoder(DecoderOptions options);

const RegisterDecoder& register_decoder();

}  // namespace pvtap::dissector
