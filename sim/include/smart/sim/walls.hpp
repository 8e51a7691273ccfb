// Contract: pure geometry of a disc (a robot) against the blocked cells of a grid map, in the
// world frame of grid/grid.hpp. Walls are the exposed faces of blocked cells (a face next to
// a free cell) as half-planes and their convex corners (a grid vertex touched by exactly one
// blocked cell) as points; outside the map counts as blocked. This is the grid-face wall model
// of docs/simulation.md: flat walls without the dents of per-cell spheres.
#pragma once

#include <vector>

#include "smart/grid/grid.hpp"

namespace smart::sim {

struct WallContact {
  double depth_m;  // penetration, > 0
  double nx, ny;   // unit normal from the wall towards the disc centre
};

// Appends the contacts of a disc of radius r (r <= cell_m / 2) centred at (x, y).
void wall_contacts(const grid::Grid& grid, double cell_m, double x_m, double y_m, double r_m,
                   std::vector<WallContact>& out);

// Cell containing a world point (may be outside the map).
grid::Cell cell_at(const grid::Grid& grid, double cell_m, double x_m, double y_m);

}  // namespace smart::sim
