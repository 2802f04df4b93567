// OutageWarnings: which changes of the broker connection are worth a line on stderr.
#pragma once

namespace pvtap::analyzer {

// A line once per outage, not once per retry; none while the first connection is made, whose
// failure the caller reports as an error.
class OutageWarnings {
 public:
  // The first connection is made: warnings start.
  void running() { starting_ = false; }
  // The broker refused a reconnection: true when that deserves a warning.
  bool refused();
  // The connection came up: true when an outage was reported (the broker "is back").
  bool back();
  // The connection went down (`own`: by our disconnect): true when that deserves a warning.
  bool lost(bool own);

 private:
  bool starting_ = true;
  bool outage_reported_ = false;
  bool refusal_reported_ = false;
};

}  // namespace pvtap::analyzer
