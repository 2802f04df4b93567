// How a station's name is learnt from the replies in which it names itself.
#pragma once

#include "pvtap/session/bus_report.h"
#include "pvtap/session/bus_session.h"

namespace pvtap {

// Takes into `name` what a good reply says of its device: the vendor, product and revision of
// a device identification (0x2B/0x0E), or, from a station of the Modbus family, the text of
// report server ID (Hybrid's 0x11 is another function). True when `name` changed: a logger asks
// the same question again and again, and only a change is copied.
bool learn_device_name(DeviceName& name, const SessionFrame& f);

}  // namespace pvtap
