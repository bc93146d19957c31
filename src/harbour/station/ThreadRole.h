#pragma once

namespace harbour::station {

/// What a station's thread does: it names the thread (as `top -H`, `perf` and debuggers show it) and sets
/// how the scheduler treats it, so that the work a trainee or an instructor waits for comes first.
enum class ThreadRole {
  kStep,          ///< the real-time loop: woken within ~1 us of its tick
  kRecordKeeper,  ///< the shadow simulation, evaluation, recording and database writes: in the background
  kMonitor,       ///< hot-plug, head tracking, motion platform frames
};

/// Gives the calling thread its role. The record keeper runs as a batch thread 10 nice levels below the
/// process (its queue holds 32 s: it catches up when the machine has time), so that on a machine shared
/// with other stations, a console and browsers it never delays a step or a command's answer. Only lowers
/// priorities: needs no privilege, and a failure leaves the thread as it was.
void take_role(ThreadRole role);

}  // namespace harbour::station
