// Contract: the time an agent reports in its RobotState samples. A physical robot's host has no
// run clock of its own (its steady clock is its uptime); what viewers and logs want is the time
// since the run began (issue 26: `smart serve --watch` showed a JetBot host's 3272 s uptime as
// the run clock 15 s into a run). RunClock counts from the first step of each run the agent
// takes part in (its first window's run id), and from the agent's start before any run. Pure:
// told the time, never reads a clock.
#pragma once

#include <cstdint>

namespace smart::agent {

class RunClock {
 public:
  // Seconds since `run_id` began for this agent, at host time now_s; a new run id restarts it.
  double since_run_start(uint64_t run_id, double now_s) {
    if (!started_ || run_id != run_id_) {
      started_ = true;
      run_id_ = run_id;
      start_s_ = now_s;
    }
    return now_s - start_s_;
  }

 private:
  bool started_ = false;
  uint64_t run_id_ = 0;
  double start_s_ = 0;
};

}  // namespace smart::agent
