#include "smart/sim/walls.hpp"

#include <cmath>

namespace smart::sim {

namespace {

bool blocked(const grid::Grid& g, int32_t col, int32_t row) {
  return !g.inside({col, row}) || g.blocked({col, row});
}

// Number of blocked cells among the four sharing the vertex at the (+sx, +sy) corner of cell
// (col, row), with sx, sy in {-1, +1} in world directions (+y is row - 1).
int blocked_around_vertex(const grid::Grid& g, int32_t col, int32_t row, int sx, int sy) {
  const int32_t dc = sx, dr = -sy;
  return blocked(g, col, row) + blocked(g, col + dc, row) + blocked(g, col, row + dr) +
         blocked(g, col + dc, row + dr);
}

}  // namespace

grid::Cell cell_at(const grid::Grid& g, double cell_m, double x, double y) {
  return {static_cast<int32_t>(std::lround(x / cell_m)),
          static_cast<int32_t>(g.height() - 1 - std::lround(y / cell_m))};
}

void wall_contacts(const grid::Grid& g, double cell_m, double x, double y, double r,
                   std::vector<WallContact>& out) {
  const auto c = cell_at(g, cell_m, x, y);
  const double half = cell_m / 2;
  // Fast path, the common case: a disc inside its own free cell touches nothing, since every
  // wall face or corner near it lies on that cell's border or beyond.
  if (!blocked(g, c.x, c.y)) {
    const double ox = x - c.x * cell_m, oy = y - (g.height() - 1 - c.y) * cell_m;
    if (std::abs(ox) + r < half && std::abs(oy) + r < half) return;
  }
  for (int dr = -1; dr <= 1; ++dr) {
    for (int dc = -1; dc <= 1; ++dc) {
      const int32_t col = c.x + dc, row = c.y + dr;
      if (!blocked(g, col, row)) continue;
      const double cx = col * cell_m, cy = (g.height() - 1 - row) * cell_m;
      // Faces: outward normal (nx, ny), the free neighbour across it, and the face's extent.
      struct Face {
        int nx, ny;
      };
      for (const Face f : {Face{1, 0}, Face{-1, 0}, Face{0, 1}, Face{0, -1}}) {
        if (blocked(g, col + f.nx, row - f.ny)) continue;  // interior face
        // Signed distance of the centre in front of the face plane.
        const double dist = (x - (cx + f.nx * half)) * f.nx + (y - (cy + f.ny * half)) * f.ny;
        // Only the face the centre is in front of (or has not passed by half a cell): the far
        // faces of a blocked cell must not pull a robot through it.
        if (dist >= r || dist <= -half) continue;
        // Position along the face, from one vertex (t = 0) to the other (t = 1).
        const double along = f.nx != 0 ? y - (cy - half) : x - (cx - half);
        const double t = along / cell_m;
        if (t < 0 || t >= 1) continue;  // beyond the face: a corner or a neighbour's face
        if (t == 0) {
          const int sx = f.nx != 0 ? f.nx : -1, sy = f.ny != 0 ? f.ny : -1;
          if (blocked_around_vertex(g, col, row, sx, sy) == 1) continue;  // the corner has it
        }
        out.push_back({r - dist, static_cast<double>(f.nx), static_cast<double>(f.ny)});
      }
      // Convex corners.
      for (int sx = -1; sx <= 1; sx += 2) {
        for (int sy = -1; sy <= 1; sy += 2) {
          if (blocked_around_vertex(g, col, row, sx, sy) != 1) continue;
          const double vx = cx + sx * half, vy = cy + sy * half;
          const double ex = x - vx, ey = y - vy;
          // Only when the centre is in the corner's own quadrant (else a face is closer).
          if (ex * sx <= 0 || ey * sy <= 0) continue;
          const double d = std::hypot(ex, ey);
          if (d >= r || d == 0) continue;
          out.push_back({r - d, ex / d, ey / d});
        }
      }
    }
  }
}

}  // namespace smart::sim
