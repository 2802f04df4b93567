// ProtocolChoices: which protocol settings the user gave; the others may come from the input.
#pragma once

namespace pvtap::analyzer {

// A capture pvtap wrote carries its run's dialects, baud rate and timeout (RunFacts): they
// apply unless the command line gave the setting.
struct ProtocolChoices {
  bool dialects = false;
  bool baud = false;
  bool timeout = false;
};

}  // namespace pvtap::analyzer
