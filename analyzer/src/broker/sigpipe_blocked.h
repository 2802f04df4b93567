// SIGPIPE blocked for a scope in which libmosquitto may write to a broker that is gone.
#pragma once

#include <pthread.h>

#include <csignal>
#include <ctime>

namespace pvtap::analyzer {

// libmosquitto writes to its socket from its own thread, and from the caller's when it
// connects, publishes or disconnects: a broker that went away must give that write EPIPE, not
// kill pvtap with SIGPIPE. Threads inherit the mask of their creator, so SIGPIPE is blocked
// while the client connects and starts its thread (and while the main thread publishes or
// disconnects), then restored.
class SigpipeBlocked {
 public:
  SigpipeBlocked(const SigpipeBlocked&) = delete;
  SigpipeBlocked& operator=(const SigpipeBlocked&) = delete;
  SigpipeBlocked() {
    sigset_t pipe;
    sigemptyset(&pipe);
    sigaddset(&pipe, SIGPIPE);
    pthread_sigmask(SIG_BLOCK, &pipe, &saved_);
  }
  // A write to a broker that had gone (a TLS alert after a failed handshake) leaves SIGPIPE
  // pending while it is blocked; it is taken here, or restoring the mask would deliver it.
  ~SigpipeBlocked() {
    sigset_t pending;
    sigpending(&pending);
    if (sigismember(&pending, SIGPIPE) == 1) {
      sigset_t pipe;
      sigemptyset(&pipe);
      sigaddset(&pipe, SIGPIPE);
      const timespec now{0, 0};
      sigtimedwait(&pipe, nullptr, &now);
    }
    pthread_sigmask(SIG_SETMASK, &saved_, nullptr);
  }

 private:
  sigset_t saved_;
};

}  // namespace pvtap::analyzer
