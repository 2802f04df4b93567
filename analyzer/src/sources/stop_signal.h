// StopSignal: SIGINT and SIGTERM ask a live capture to stop; reading loops poll the flag.
#pragma once

namespace pvtap::analyzer {

// Installs handlers for SIGINT and SIGTERM that only set a flag. Without SA_RESTART, so that
// a blocking poll() or read() returns EINTR and the loop sees the request at once.
void install_stop_handlers();

// True once SIGINT or SIGTERM arrived (or request_stop() was called).
bool stop_requested();

// Asks the reading loop to stop, as the signals do (--count, --duration).
void request_stop();

}  // namespace pvtap::analyzer
