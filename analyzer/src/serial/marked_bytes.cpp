// MarkedBytes: a three-state reader of PARMRK escapes.
#include "serial/marked_bytes.h"

namespace pvtap::analyzer {

void MarkedBytes::unmark(std::span<const std::uint8_t> in, std::vector<LineByte>& out) {
  for (const std::uint8_t c : in) {
    switch (state_) {
      case State::Plain:
        if (c == 0xFF) {
          state_ = State::Escape;
        } else {
          out.push_back(LineByte{c, false, false});
        }
        break;
      case State::Escape:
        if (c == 0x00) {
          state_ = State::EscapeZero;
        } else {
          // \377 \377 is a \377; anything else after \377 the driver never writes, and the
          // \377 is kept rather than lost.
          out.push_back(LineByte{0xFF, false, false});
          state_ = State::Plain;
          if (c != 0xFF) out.push_back(LineByte{c, false, false});
        }
        break;
      case State::EscapeZero:
        out.push_back(LineByte{c, true, false});
        state_ = State::Plain;
        break;
    }
  }
}

}  // namespace pvtap::analyzer
