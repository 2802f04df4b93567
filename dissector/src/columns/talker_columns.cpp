#include "columns/talker_columns.h"

namespace pvtap::dissector {
namespace {

// Names the master in `list` unless it is named already.
void add_master(TalkerList& list, wmem_allocator_t* pool) {
  if (list.master) return;
  list.master = true;
  list.text = list.text == nullptr ? "master" : wmem_strdup_printf(pool, "%s, master", list.text);
}

// Names `station` in `list` unless it is named already.
void add_station(TalkerList& list, std::uint8_t station, wmem_allocator_t* pool) {
  const auto bit = static_cast<std::uint8_t>(1U << (station % 8));
  std::uint8_t& named = list.stations[station / 8];
  if ((named & bit) != 0) return;
  named = static_cast<std::uint8_t>(named | bit);
  list.text = list.text == nullptr ? wmem_strdup_printf(pool, "station %u", station)
                                   : wmem_strdup_printf(pool, "%s, station %u", list.text, station);
}

}  // namespace

void add_talkers(TalkerColumns& columns, const FrameRecord& frame, wmem_allocator_t* pool) {
  if (!frame.matched) return;
  const bool request = frame.role == Role::Request;
  TalkerList& master_side = request ? columns.source : columns.destination;
  TalkerList& station_side = request ? columns.destination : columns.source;
  add_master(master_side, pool);
  add_station(station_side, frame.station, pool);
}

void write_talkers(const TalkerColumns& columns, packet_info* pinfo) {
  if (columns.source.text != nullptr) {
    col_add_str(pinfo->cinfo, COL_RES_DL_SRC, columns.source.text);
  }
  if (columns.destination.text != nullptr) {
    col_add_str(pinfo->cinfo, COL_RES_DL_DST, columns.destination.text);
  }
}

}  // namespace pvtap::dissector
