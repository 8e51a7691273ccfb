// Contract: who does which task. A Scheduler is asked, whenever robots are free (no task), to
// pick for each free robot one of the revealed tasks nobody holds, or none; it never sees an
// opened task (LoRR: a task whose first errand is done stays with its robot). The default,
// GreedyNearestScheduler: free robots in id order each take the task whose first errand is
// nearest (Manhattan distance on the grid; ties to the earliest revealed task). Manhattan, not
// the true distance, so that 10 000 robots over thousands of tasks cost no distance tables; on
// maps with long walls it may pick a task that is close as the crow flies. Pure, deterministic.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "smart/grid/grid.hpp"

namespace smart::lifelong {

struct OpenTask {
  uint64_t task = 0;
  grid::Cell first;  // its first errand
};

class Scheduler {
 public:
  virtual ~Scheduler() = default;
  // (robot, task) pairs: each robot of `free` at most once, each task at most once.
  virtual std::vector<std::pair<uint32_t, uint64_t>> assign(const std::vector<uint32_t>& free,
                                                            const std::vector<grid::Cell>& cells,
                                                            const std::vector<OpenTask>& open) = 0;
};

class GreedyNearestScheduler final : public Scheduler {
 public:
  std::vector<std::pair<uint32_t, uint64_t>> assign(const std::vector<uint32_t>& free,
                                                    const std::vector<grid::Cell>& cells,
                                                    const std::vector<OpenTask>& open) override;
};

}  // namespace smart::lifelong
