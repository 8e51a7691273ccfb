#include "smart/planning/guide_paths.hpp"

#include <algorithm>
#include <cstdlib>

#include "smart/planning/generators.hpp"

namespace smart::planning {

namespace {
constexpr std::size_t kReach = 64;    // how far along its path a robot is looked for
constexpr int32_t kRepairDepth = 12;  // how far a displaced robot looks for its path
}  // namespace

GuidePaths::GuidePaths(const grid::Grid& grid, int landmarks, std::size_t searches_per_window)
    : grid_(grid),
      width_(grid.width()),
      landmarks_(static_cast<std::size_t>(landmarks)),
      searches_per_window_(searches_per_window),
      searches_left_(searches_per_window) {
  const std::size_t cells = static_cast<std::size_t>(grid.width()) * grid.height();
  g_.assign(cells, 0);
  parent_.assign(cells, 0);
  seen_.assign(cells, 0);
  const auto region = largest_region_cells(grid);
  if (region.empty()) landmarks_ = 0;
  landmark_.assign(cells * landmarks_, -1);
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
      landmark_[c * landmarks_ + k] = d[c];
      if (k == 0) nearest[c] = INT32_MAX;
      if (d[c] >= 0) nearest[c] = std::min(nearest[c], d[c]);
    }
  }
}

int32_t GuidePaths::h(uint32_t v, uint32_t goal) const {
  int32_t best = std::abs(static_cast<int32_t>(v % width_) - static_cast<int32_t>(goal % width_)) +
                 std::abs(static_cast<int32_t>(v / width_) - static_cast<int32_t>(goal / width_));
  const int32_t* a = landmark_.data() + static_cast<std::size_t>(v) * landmarks_;
  const int32_t* b = landmark_.data() + static_cast<std::size_t>(goal) * landmarks_;
  for (std::size_t k = 0; k < landmarks_; ++k) {
    if (a[k] >= 0 && b[k] >= 0) best = std::max(best, std::abs(a[k] - b[k]));
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

// A* from `from` to `to`; ties prefer the deeper node (fewer expansions on open ground).
bool GuidePaths::search(uint32_t from, uint32_t to, std::vector<uint32_t>& out) {
  ++searches_;
  if (++stamp_ == 0) {
    std::fill(seen_.begin(), seen_.end(), 0);
    stamp_ = 1;
  }
  const auto worse = [](const Open& a, const Open& b) {
    return a.f != b.f ? a.f > b.f : a.g < b.g;
  };
  heap_.clear();
  seen_[from] = stamp_;
  g_[from] = 0;
  parent_[from] = from;
  heap_.push_back({h(from, to), 0, from});
  const auto w = static_cast<uint32_t>(width_);
  const auto cells = static_cast<uint32_t>(seen_.size());
  while (!heap_.empty()) {
    std::pop_heap(heap_.begin(), heap_.end(), worse);
    const Open n = heap_.back();
    heap_.pop_back();
    if (n.g != g_[n.cell]) continue;  // a stale entry
    if (n.cell == to) {
      out.clear();
      for (uint32_t c = to; c != from; c = parent_[c]) out.push_back(c);
      out.push_back(from);
      std::reverse(out.begin(), out.end());
      return true;
    }
    ++expanded_;
    const uint32_t x = n.cell % w;
    const uint32_t next[4] = {x + 1 < w ? n.cell + 1 : UINT32_MAX, x > 0 ? n.cell - 1 : UINT32_MAX,
                              n.cell + w < cells ? n.cell + w : UINT32_MAX,
                              n.cell >= w ? n.cell - w : UINT32_MAX};
    for (const uint32_t m : next) {
      if (m == UINT32_MAX ||
          grid_.blocked({static_cast<int32_t>(m % w), static_cast<int32_t>(m / w)})) {
        continue;
      }
      const int32_t ng = n.g + 1;
      if (seen_[m] == stamp_ && g_[m] <= ng) continue;
      seen_[m] = stamp_;
      g_[m] = ng;
      parent_[m] = n.cell;
      heap_.push_back({ng + h(m, to), ng, m});
      std::push_heap(heap_.begin(), heap_.end(), worse);
    }
  }
  return false;
}

std::vector<grid::Cell> GuidePaths::shortest_path(grid::Cell from, grid::Cell to) {
  std::vector<grid::Cell> out;
  if (!grid_.free(from) || !grid_.free(to)) return out;
  std::vector<uint32_t> cells;
  if (!search(static_cast<uint32_t>(grid_.index(from)), static_cast<uint32_t>(grid_.index(to)),
              cells)) {
    return out;
  }
  for (const auto c : cells)
    out.push_back({static_cast<int32_t>(c % width_), static_cast<int32_t>(c / width_)});
  return out;
}

// The robot is on its path near where it was last seen (a window's cut may lie behind where
// the last window ended), or a cell off it: keep the path.
bool GuidePaths::rejoin(Guide& p, uint32_t at) const {
  const std::size_t begin = p.idx > kReach ? p.idx - kReach : 0;
  const std::size_t end = std::min(p.cells.size(), std::size_t{p.idx} + kReach);
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
  const std::size_t begin = p.idx > kReach ? p.idx - kReach : 0;
  const std::size_t end = std::min(p.cells.size(), std::size_t{p.idx} + kReach);
  if (++stamp_ == 0) {
    std::fill(seen_.begin(), seen_.end(), 0);
    stamp_ = 1;
  }
  const uint32_t path_mark = stamp_;
  for (std::size_t k = begin; k < end; ++k) {
    seen_[p.cells[k]] = path_mark;
    g_[p.cells[k]] = static_cast<int32_t>(k);
  }
  if (++stamp_ == 0) return false;  // (never in practice: 4 billion searches)
  const auto w = static_cast<uint32_t>(width_);
  const auto cells = static_cast<uint32_t>(seen_.size());
  queue_.assign(1, at);
  std::vector<int32_t> depth{0};
  parent_[at] = at;
  seen_[at] = stamp_;
  for (std::size_t head = 0; head < queue_.size(); ++head) {
    const uint32_t c = queue_[head];
    if (seen_[c] == path_mark) {  // reached the path at index g_[c]
      const auto k = static_cast<std::size_t>(g_[c]);
      std::vector<uint32_t> way;
      for (uint32_t v = c; v != at; v = parent_[v]) way.push_back(v);
      way.push_back(at);
      std::reverse(way.begin(), way.end());
      way.insert(way.end(), p.cells.begin() + static_cast<long>(k) + 1, p.cells.end());
      p.cells = std::move(way);
      p.idx = 0;
      p.off = false;
      ++repairs_;
      return true;
    }
    if (depth[head] == kRepairDepth) continue;
    const uint32_t x = c % w;
    const uint32_t next[4] = {x + 1 < w ? c + 1 : UINT32_MAX, x > 0 ? c - 1 : UINT32_MAX,
                              c + w < cells ? c + w : UINT32_MAX, c >= w ? c - w : UINT32_MAX};
    for (const uint32_t m : next) {
      if (m == UINT32_MAX || seen_[m] == stamp_ ||
          grid_.blocked({static_cast<int32_t>(m % w), static_cast<int32_t>(m / w)})) {
        continue;
      }
      if (seen_[m] != path_mark) seen_[m] = stamp_;
      parent_[m] = c;
      queue_.push_back(m);
      depth.push_back(depth[head] + 1);
    }
  }
  return false;
}

bool GuidePaths::aim(uint32_t robot, grid::Cell at, grid::Cell goal) {
  if (robot >= guides_.size()) guides_.resize(robot + 1);
  auto& p = guides_[robot];
  const auto a = static_cast<uint32_t>(grid_.index(at)),
             g = static_cast<uint32_t>(grid_.index(goal));
  if (p.goal == g && !p.waiting && !p.cells.empty() && (rejoin(p, a) || repair(p, a))) {
    return true;
  }
  p.idx = 0;
  p.off = false;
  p.waiting = false;
  if (a == g) {
    p.goal = g;
    p.cells.assign(1, a);
    return true;
  }
  if (!grid_.free(goal)) {
    p.goal = UINT32_MAX;
    p.cells.assign(1, a);
    return false;
  }
  if (searches_left_ == 0) {  // later: the landmark bound meanwhile
    p.goal = g;
    p.cells.assign(1, a);
    p.waiting = true;
    return true;
  }
  --searches_left_;
  if (!search(a, g, p.cells)) {
    p.goal = UINT32_MAX;
    p.cells.assign(1, a);  // rank as holding still
    return false;
  }
  p.goal = g;
  return true;
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
  std::size_t paths = 0;
  for (const auto& p : guides_) paths += p.cells.capacity() * sizeof(uint32_t);
  return landmark_.size() * sizeof(int32_t) + g_.size() * (sizeof(int32_t) + 2 * sizeof(uint32_t)) +
         paths;
}

}  // namespace smart::planning
