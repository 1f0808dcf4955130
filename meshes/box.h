// A structured hexahedral box [0, Lx] x [0, Ly] x [0, Lz] from gmsh, for solver checks.
// Boundary ids: 1 x = 0, 2 x = Lx, 3 y = 0, 4 y = Ly, 5 z = 0, 6 z = Lz; volume 1 "body".
#pragma once

#include "geometry/types.h"

#include <string>

namespace gearkit
{
/// Writes the box mesh (nx x ny x nz hexahedra) to `path` (.msh 4.1) and `path`.json.
void
write_box_mesh(const Vec3 &size, int nx, int ny, int nz, const std::string &path);
} // namespace gearkit
