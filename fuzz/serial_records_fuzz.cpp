// Fuzz target serial_records: the exported-PDU (link type 252) tag reader (pvtap's own tags
// included) and the RTAC serial (link type 250) header reader on arbitrary records. What they
// return must lie inside the record. The first byte picks the reader; both read the rest.
#include <cstddef>
#include <cstdint>
#include <span>

#include "fuzz_input.h"
#include "pvtap/pcap/exported_pdu_reader.h"
#include "pvtap/pcap/rtac_record.h"

namespace {

bool inside(std::span<const std::uint8_t> part, std::span<const std::uint8_t> whole) {
  if (part.empty()) return true;
  return part.data() >= whole.data() && part.data() + part.size() <= whole.data() + whole.size();
}

void read_rtac(std::span<const std::uint8_t> record) {
  const auto r = pvtap::rtac_serial_record(record);
  if (!r) {
    PVTAP_FUZZ_CHECK(record.size() < 12);
    return;
  }
  PVTAP_FUZZ_CHECK(inside(r->bytes, record));
  PVTAP_FUZZ_CHECK(r->bytes.size() + 12 <= record.size());
}

void read_exported_pdu(std::span<const std::uint8_t> record) {
  const auto r = pvtap::exported_pdu_record(record);
  if (!r) return;
  PVTAP_FUZZ_CHECK(inside(r->pdu, record));
  const std::span<const std::uint8_t> name(
      reinterpret_cast<const std::uint8_t*>(r->dissector.data()), r->dissector.size());
  PVTAP_FUZZ_CHECK(inside(name, record));
  // pvtap's own tags: their values lie inside the record, and the bus name inside the run's.
  PVTAP_FUZZ_CHECK(inside(r->pvtap_record, record) && inside(r->pvtap_run, record));
  if (const auto facts = pvtap::record_facts(r->pvtap_record)) {
    PVTAP_FUZZ_CHECK(pvtap::index_of(facts->stream) < pvtap::kDirections);
  }
  if (const auto run = pvtap::run_facts(r->pvtap_run)) {
    const std::span<const std::uint8_t> bus(reinterpret_cast<const std::uint8_t*>(run->bus.data()),
                                            run->bus.size());
    PVTAP_FUZZ_CHECK(inside(bus, r->pvtap_run));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  pvtap::fuzz::FuzzInput in(data, size);
  const std::uint8_t selector = in.byte();
  const auto record = in.rest();
  if (selector & 1u) {
    read_rtac(record);
  } else {
    read_exported_pdu(record);
  }
  return 0;
}
