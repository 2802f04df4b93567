#include "bus/poll_blocks.h"

#include <array>

#include "pvtap/codec/function_codes.h"

namespace pvtap::sim {
namespace {

constexpr std::array kAsciiBlocks{
    PollBlock{fc::kAsciiRead, 0x01E0, 3, true},  PollBlock{fc::kAsciiRead, 0x0004, 4, false},
    PollBlock{fc::kAsciiRead, 0x0020, 2, false}, PollBlock{fc::kAsciiRead, 0x0050, 7, false},
    PollBlock{fc::kAsciiRead, 0x0060, 8, false},
};

constexpr std::array kHybridBlocks{
    PollBlock{fc::kHybridDeviceInfo, 0x1060, 0x0002, true},
    PollBlock{fc::kHybridSettings, 0x1024, 0x0027, true},
    PollBlock{fc::kHybridRunningData, 0x1000, 0x0024, false},
};

// GSL IDs 1000.. (names), 1030.. (alarm and status words), 1050..1095 (measurements).
constexpr std::array kGslBlocks{
    PollBlock{fc::kGslReadHolding, 1000, 10, true},
    PollBlock{fc::kGslReadHolding, 1030, 4, false},
    PollBlock{fc::kGslReadHolding, 1050, 46, false},
};

}  // namespace

std::span<const PollBlock> poll_blocks(Dialect dialect) {
  switch (dialect) {
    case Dialect::Ascii:
      return kAsciiBlocks;
    case Dialect::Hybrid:
      return kHybridBlocks;
    case Dialect::Gsl:
      return kGslBlocks;
    case Dialect::Modbus:
      break;  // plain Modbus devices poll their own blocks
  }
  return {};
}

}  // namespace pvtap::sim
