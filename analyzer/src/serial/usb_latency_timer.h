// UsbLatencyTimer: the latency timer of an FTDI USB serial adapter, read and lowered via sysfs.
//
// An FTDI chip holds received bytes until its buffer fills or the timer runs out (16 ms by
// default), so every read returns a batch stamped at the batch's end. At 1 ms the stamps are
// fine enough to see the bus's t3.5 silences at usual baud rates.
#pragma once

#include <optional>
#include <string>

namespace pvtap::analyzer {

struct LatencyTimerState {
  std::optional<int> ms;  // nullopt: the adapter has no latency timer (not FTDI, a pty)
  std::string note;       // what was done: "lowered from 16 ms", "cannot lower: ..."
  std::string adapter;    // the tty the device path resolves to, e.g. "ttyUSB0"
};

// TtyPlaces: where device nodes and the kernel's tty attributes are; tests point elsewhere.
struct TtyPlaces {
  std::string dev = "/dev";
  std::string sys_class_tty = "/sys/class/tty";
};

// Reads the latency timer of the adapter behind `device_path` (symlinks such as
// /dev/serial/by-id/... are followed) and sets it to 1 ms when it is higher and writable.
LatencyTimerState lower_latency_timer(const std::string& device_path, const TtyPlaces& places = {});

}  // namespace pvtap::analyzer
