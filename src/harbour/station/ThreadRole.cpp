#include "harbour/station/ThreadRole.h"

#include <pthread.h>
#include <sched.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>

namespace harbour::station {
namespace {
constexpr int kBackgroundNice = 10;  // a nice-10 thread gets about a tenth of a nice-0 one's share
constexpr int kLowestNice = 19;
}  // namespace

void take_role(ThreadRole role) {
  switch (role) {
    case ThreadRole::kStep:
      pthread_setname_np(pthread_self(), "hs-step");
      prctl(PR_SET_TIMERSLACK, 1000UL);  // wake within ~1 us of the tick, not the default 50 us
      break;
    case ThreadRole::kRecordKeeper: {
      pthread_setname_np(pthread_self(), "hs-keeper");
      // on Linux, these calls with 0 / the thread id act on the calling thread alone
      const sched_param batch{};
      sched_setscheduler(0, SCHED_BATCH, &batch);
      const auto thread = static_cast<id_t>(gettid());
      const int nice = getpriority(PRIO_PROCESS, thread);
      setpriority(PRIO_PROCESS, thread, std::min(nice + kBackgroundNice, kLowestNice));
      break;
    }
    case ThreadRole::kMonitor:
      pthread_setname_np(pthread_self(), "hs-monitor");
      break;
  }
}

}  // namespace harbour::station
