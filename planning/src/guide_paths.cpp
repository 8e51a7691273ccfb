#include "smart/planning/guide_paths.hpp"

#include <algorithm>
#include <cstdlib>
#include <thread>

#include "smart/planning/generators.hpp"

namespace smart::planning {

namespace {
constexpr std::size_t kReach = 64;     // how far along its path a robot is looked for
constexpr int32_t kRepairDepth = 12;   // how far a displaced robot looks for its path
constexpr uint16_t kFar = UINT16_MAX;  // a landmark's table: no path
constexpr int32_t kClamp = UINT16_MAX - 1;
}  // namespace

GuidePaths::GuidePaths(const grid::Grid& grid, int landmarks, std::size_t searches_per_window,
                       unsigned threads)
    : grid_(grid),
      width_(grid.width()),
      landmarks_(static_cast<std::size_t>(landmarks)),
      searches_per_window_(searches_per_window),
      searches_left_(searches_per_window) {
  const std::size_t cells = static_cast<std::size_t>(grid.width()) * grid.height();
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  for (unsigned t = 0; t < threads; ++t) work_.emplace_back(cells);
  const auto region = largest_region_cells(grid);
  if (region.empty()) landmarks_ = 0;
  landmark_.assign(cells * landmarks_, kFar);
  // Farthest-first: each landmark is the region's cell farthest from those chosen (the first,
  // farthest from the region's first cell), so some landmark lies "behind" most goals.
  std::vector<int32_t> nearest(cells, INT32_MAX);
  if (!region.empty()) {
    const auto d = bfs_distances(grid, region.front());
    for (const auto c : region) nearest[grid.index(c)] = d[grid.index(c)];
  }
  for (std::size_t k = 0; k < landmarks_; ++k) {
    grid::Cell far = region.front();
    int32_t best = -1;
    for (const auto c : region) {
      if (nearest[grid.index(c)] > best) best = nearest[grid.index(c)], far = c;
    }
    const auto d = bfs_distances(grid, far);
    for (std::size_t c = 0; c < cells; ++c) {
      landmark_[c * landmarks_ + k] =
          d[c] < 0 ? kFar : static_cast<uint16_t>(std::min(d[c], kClamp));
      if (k == 0) nearest[c] = INT32_MAX;
      if (d[c] >= 0) nearest[c] = std::min(nearest[c], d[c]);
    }
  }
}

int32_t GuidePaths::h(uint32_t v, uint32_t goal) const {
  int32_t best = std::abs(static_cast<int32_t>(v % width_) - static_cast<int32_t>(goal % width_)) +
                 std::abs(static_cast<int32_t>(v / width_) - static_cast<int32_t>(goal / width_));
  const uint16_t* a = landmark_.data() + static_cast<std::size_t>(v) * landmarks_;
  const uint16_t* b = landmark_.data() + static_cast<std::size_t>(goal) * landmarks_;
  for (std::size_t k = 0; k < landmarks_; ++k) {
    if (a[k] != kFar && b[k] != kFar) {
      best = std::max(best, std::abs(int32_t{a[k]} - int32_t{b[k]}));
    }
  }
  return best;
}

int32_t GuidePaths::lower_bound(grid::Cell a, grid::Cell b) const {
  return h(static_cast<uint32_t>(grid_.index(a)), static_cast<uint32_t>(grid_.index(b)));
}

bool GuidePaths::adjacent(uint32_t a, uint32_t b) const {
  const auto w = static_cast<uint32_t>(width_);
  const uint32_t lo = std::min(a, b), hi = std::max(a, b);
  return hi - lo == w || (hi - lo == 1 && hi % w != 0);
}

grid::Cell GuidePaths::cell_of(uint32_t v) const {
  return {static_cast<int32_t>(v % static_cast<uint32_t>(width_)),
          static_cast<int32_t>(v / static_cast<uint32_t>(width_))};
}

// The free 4-neighbours of cell index `c` into `out`; returns how many.
int GuidePaths::free_neighbours(uint32_t c, uint32_t (&out)[4]) const {
  const auto w = static_cast<uint32_t>(width_);
  const auto cells = w * static_cast<uint32_t>(grid_.height());
  const uint32_t x = c % w;
  const uint32_t next[4] = {x + 1 < w ? c + 1 : UINT32_MAX, x > 0 ? c - 1 : UINT32_MAX,
                            c + w < cells ? c + w : UINT32_MAX, c >= w ? c - w : UINT32_MAX};
  int n = 0;
  for (const uint32_t m : next) {
    if (m != UINT32_MAX && !grid_.blocked(cell_of(m))) out[n++] = m;
  }
  return n;
}

// Where a robot may be found on its path: kReach cells either side of where it was.
std::pair<std::size_t, std::size_t> GuidePaths::near(const Guide& p) {
  return {p.idx > kReach ? p.idx - kReach : 0,
          std::min(p.cells.size(), std::size_t{p.idx} + kReach)};
}

uint32_t GuidePaths::Workspace::next_stamp() {
  if (++stamp == 0) {
    std::fill(seen.begin(), seen.end(), 0);
    stamp = 1;
  }
  return stamp;
}

// A* from `from` to `to`; ties prefer the deeper node (fewer expansions on open ground).
bool GuidePaths::search(Workspace& w, uint32_t from, uint32_t to,
                        std::vector<uint32_t>& out) const {
  const uint32_t stamp = w.next_stamp();
  const auto worse = [](const Open& a, const Open& b) {
    return a.f != b.f ? a.f > b.f : a.g < b.g;
  };
  w.heap.clear();
  w.seen[from] = stamp;
  w.g[from] = 0;
  w.parent[from] = from;
  w.heap.push_back({h(from, to), 0, from});
  while (!w.heap.empty()) {
    std::pop_heap(w.heap.begin(), w.heap.end(), worse);
    const Open n = w.heap.back();
    w.heap.pop_back();
    if (n.g != w.g[n.cell]) continue;  // a stale entry
    if (n.cell == to) {
      out.clear();
      for (uint32_t c = to; c != from; c = w.parent[c]) out.push_back(c);
      out.push_back(from);
      std::reverse(out.begin(), out.end());
      return true;
    }
    ++w.expanded;
    uint32_t next[4];
    const int count = free_neighbours(n.cell, next);
    for (int i = 0; i < count; ++i) {
      const uint32_t m = next[i];
      const int32_t ng = n.g + 1;
      if (w.seen[m] == stamp && w.g[m] <= ng) continue;
      w.seen[m] = stamp;
      w.g[m] = ng;
      w.parent[m] = n.cell;
      w.heap.push_back({ng + h(m, to), ng, m});
      std::push_heap(w.heap.begin(), w.heap.end(), worse);
    }
  }
  return false;
}

std::size_t GuidePaths::expanded() const {
  std::size_t sum = 0;
  for (const auto& w : work_) sum += w.expanded;
  return sum;
}

std::vector<grid::Cell> GuidePaths::shortest_path(grid::Cell from, grid::Cell to) {
  std::vector<grid::Cell> out;
  if (!grid_.free(from) || !grid_.free(to)) return out;
  std::vector<uint32_t> cells;
  ++searches_;
  if (!search(work_.front(), static_cast<uint32_t>(grid_.index(from)),
              static_cast<uint32_t>(grid_.index(to)), cells)) {
    return out;
  }
  for (const auto c : cells) out.push_back(cell_of(c));
  return out;
}

// The robot is on its path near where it was last seen (a window's cut may lie behind where
// the last window ended), or a cell off it: keep the path.
bool GuidePaths::rejoin(Guide& p, uint32_t at) const {
  const auto [begin, end] = near(p);
  for (std::size_t k = begin; k < end; ++k) {
    if (p.cells[k] == at) {
      p.idx = static_cast<uint32_t>(k);
      p.off = false;
      return true;
    }
  }
  for (std::size_t k = end; k-- > begin;) {
    if (adjacent(p.cells[k], at)) {
      p.idx = static_cast<uint32_t>(k);
      p.off = true;
      p.at = at;
      return true;
    }
  }
  return false;
}

// A BFS from `at` (at most kRepairDepth steps) to the nearest cell of the path near idx; the
// way there is prepended to the rest of the path.
bool GuidePaths::repair(Guide& p, uint32_t at) {
  const auto [begin, end] = near(p);
  auto& w = work_.front();
  const uint32_t path_mark = w.next_stamp();
  for (std::size_t k = begin; k < end; ++k) {
    w.seen[p.cells[k]] = path_mark;
    w.g[p.cells[k]] = static_cast<int32_t>(k);
  }
  const uint32_t stamp = w.next_stamp();
  if (stamp < path_mark) return false;  // the stamps wrapped (after 4 billion searches)
  w.queue.assign(1, at);
  w.depth.assign(1, 0);
  w.parent[at] = at;
  w.seen[at] = stamp;
  for (std::size_t head = 0; head < w.queue.size(); ++head) {
    const uint32_t c = w.queue[head];
    if (w.seen[c] == path_mark) {  // reached the path at index g[c]
      const auto k = static_cast<std::size_t>(w.g[c]);
      std::vector<uint32_t> way;
      for (uint32_t v = c; v != at; v = w.parent[v]) way.push_back(v);
      way.push_back(at);
      std::reverse(way.begin(), way.end());
      way.insert(way.end(), p.cells.begin() + static_cast<long>(k) + 1, p.cells.end());
      p.cells = std::move(way);
      p.idx = 0;
      p.off = false;
      ++repairs_;
      return true;
    }
    if (w.depth[head] == kRepairDepth) continue;
    uint32_t next[4];
    const int count = free_neighbours(c, next);
    for (int i = 0; i < count; ++i) {
      const uint32_t m = next[i];
      if (w.seen[m] == stamp) continue;
      if (w.seen[m] != path_mark) w.seen[m] = stamp;
      w.parent[m] = c;
      w.queue.push_back(m);
      w.depth.push_back(w.depth[head] + 1);
    }
  }
  return false;
}

bool GuidePaths::keeps(Guide& p, uint32_t at, uint32_t goal) {
  return p.goal == goal && !p.waiting && !p.cells.empty() && (rejoin(p, at) || repair(p, at));
}

bool GuidePaths::settle(Guide& p, uint32_t at, uint32_t goal) {
  p.idx = 0;
  p.off = false;
  p.waiting = false;
  p.goal = goal;
  p.cells.assign(1, at);
  if (at == goal) return true;
  if (searches_left_ > 0) return false;
  p.waiting = true;  // later: the landmark bound meanwhile
  return true;
}

void GuidePaths::found(Guide& p, uint32_t at, uint32_t goal, bool path) {
  ++searches_;
  p.idx = 0;
  p.off = false;
  p.waiting = false;
  if (searches_left_ > 0) --searches_left_;
  p.goal = path ? goal : UINT32_MAX;
  if (!path) p.cells.assign(1, at);  // ranks as holding still
}

// The window's first searches, chosen in robot order, run on the workspaces' threads.
void GuidePaths::new_window(const std::vector<grid::Cell>& at,
                            const std::vector<grid::Cell>& goal) {
  searches_left_ = searches_per_window_;
  if (guides_.size() < at.size()) guides_.resize(at.size());
  std::vector<uint32_t> batch;
  for (uint32_t r = 0; r < at.size() && batch.size() < searches_left_; ++r) {
    if (!grid_.free(at[r]) || !grid_.free(goal[r])) continue;  // aim() says why
    auto& p = guides_[r];
    const auto a = static_cast<uint32_t>(grid_.index(at[r]));
    const auto g = static_cast<uint32_t>(grid_.index(goal[r]));
    if (keeps(p, a, g) || a == g) continue;
    batch.push_back(r);
  }
  std::vector<uint8_t> ok(batch.size(), 0);
  const auto run = [&](std::size_t t) {
    for (std::size_t k = t; k < batch.size(); k += work_.size()) {
      const uint32_t r = batch[k];
      ok[k] = search(work_[t], static_cast<uint32_t>(grid_.index(at[r])),
                     static_cast<uint32_t>(grid_.index(goal[r])), guides_[r].cells);
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < work_.size() && batch.size() > 1; ++t) pool.emplace_back(run, t);
  run(0);
  for (auto& t : pool) t.join();
  for (std::size_t k = 0; k < batch.size(); ++k) {
    found(guides_[batch[k]], static_cast<uint32_t>(grid_.index(at[batch[k]])),
          static_cast<uint32_t>(grid_.index(goal[batch[k]])), ok[k] != 0);
  }
}

bool GuidePaths::aim(uint32_t robot, grid::Cell at, grid::Cell goal) {
  if (robot >= guides_.size()) guides_.resize(robot + 1);
  auto& p = guides_[robot];
  const auto a = static_cast<uint32_t>(grid_.index(at)),
             g = static_cast<uint32_t>(grid_.index(goal));
  if (!grid_.free(goal)) {
    settle(p, a, a);
    p.goal = UINT32_MAX;
    return false;
  }
  if (keeps(p, a, g) || settle(p, a, g)) return true;
  const bool path = search(work_.front(), a, g, p.cells);
  found(p, a, g, path);
  return path;
}

int64_t GuidePaths::rank(uint32_t robot, grid::Cell c) {
  const auto& p = guides_[robot];
  const auto v = static_cast<uint32_t>(grid_.index(c));
  if (p.waiting) return h(v, p.goal);
  const auto left = static_cast<int64_t>(p.cells.size() - 1 - p.idx);
  if (p.off) {  // from `at`, the way is back onto cells[idx]: left + 1
    if (v == p.cells[p.idx]) return left;
    return v == p.at ? left + 1 : left + 2;
  }
  if (v == p.cells[p.idx]) return left;
  if (p.idx + 1 < p.cells.size() && v == p.cells[p.idx + 1]) return left - 1;
  return left + 1;
}

std::size_t GuidePaths::memory_bytes() const {
  std::size_t bytes = landmark_.size() * sizeof(uint16_t);
  for (const auto& p : guides_) bytes += p.cells.capacity() * sizeof(uint32_t);
  for (const auto& w : work_) bytes += w.g.size() * (sizeof(int32_t) + 2 * sizeof(uint32_t));
  return bytes;
}

}  // namespace smart::planning
