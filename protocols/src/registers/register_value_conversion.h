// Turns the words of one complete register value into its fields (private to the core).
#pragma once

#include <cstdint>
#include <span>

#include "pvtap/registers/register_decoder.h"

namespace pvtap::detail {

// Fills raw, signed_raw, value and the kind's own fields of `v` from all words of the
// value in wire order (the entry's word order puts them high word first). `option_rule` decides
// pairs whose entry leaves the rule open.
void convert_words(const RegisterDef& def, std::span<const std::uint16_t> words,
                   PairRule option_rule, DecodedValue& v);

// The same for a device number known only from its two words, without a map entry.
void convert_device_number(const RegisterDef* def, std::span<const std::uint16_t, 2> words,
                           DecodedValue& v);

}  // namespace pvtap::detail
