// The reader of link type 252 records (Wireshark's exported PDUs), as --write writes them.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "pvtap/framing/bus_chunk.h"
#include "pvtap/pcap/pvtap_record_facts.h"

namespace pvtap {

// ExportedPdu: one record of link type 252 (Wireshark's exported PDUs): tags, then the PDU.
struct ExportedPdu {
  std::string_view dissector;  // EXP_PDU_TAG_DISSECTOR_NAME, trailing NULs removed
  Direction direction = Direction::Unknown;
  std::span<const std::uint8_t> pdu;
  // The values of pvtap's own tags (read them with record_facts and run_facts); empty in files
  // of older versions and of other writers. Kept raw: most records need neither read.
  std::span<const std::uint8_t> pvtap_record;
  std::span<const std::uint8_t> pvtap_run;
};

// Reads the tag list of a 252 record; nullopt when it is cut short or has no end tag.
std::optional<ExportedPdu> exported_pdu_record(std::span<const std::uint8_t> record);

// The values of pvtap's tags; nullopt when empty, of another version, or malformed (then the
// tag is as good as unknown).
std::optional<RecordFacts> record_facts(std::span<const std::uint8_t> pvtap_record);
std::optional<RunFacts> run_facts(std::span<const std::uint8_t> pvtap_run);

}  // namespace pvtap
