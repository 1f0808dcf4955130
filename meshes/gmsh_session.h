// Shared plumbing of the gmsh models: gmsh's global state for one model build, the all-hexahedra
// check, and atomic writes of the mesh and its .json sidecar.
#pragma once

#include <cstddef>
#include <string>

namespace gearkit
{
/// gmsh initialised (quiet) for one model build and finalised on every exit path. Errors gmsh
/// throws inside `run` become InputError naming `what`.
class GmshSession
{
public:
  GmshSession();
  ~GmshSession();
  GmshSession(const GmshSession &) = delete;
  GmshSession &
  operator=(const GmshSession &) = delete;
};

/// Runs f inside a GmshSession; gmsh's own exceptions become InputError("<what>: gmsh failed
/// (<gmsh's last error>)").
template <class F>
void
with_gmsh(const std::string &what, F &&f);

/// Throws InputError (naming `what`) unless the current model's 3-D mesh is all hexahedra;
/// returns (hexahedra, nodes).
std::pair<std::size_t, std::size_t>
require_hexahedra(const std::string &what);

/// The Jacobian of the trilinear map at corner c (0-7, gmsh/VTK order) of a hexahedron, from the
/// three edges leaving it (positive for a right-handed, unfolded corner).
template <class Point>
double
hexahedron_corner_jacobian(const Point (&x)[8], int c)
{
  static const int    along[8][3] = {{1, 3, 4}, {0, 2, 5}, {3, 1, 6}, {2, 0, 7},
                                     {5, 7, 0}, {4, 6, 1}, {7, 5, 2}, {6, 4, 3}};
  static const double sign[8]     = {1, -1, 1, -1, -1, 1, -1, 1};
  return sign[c] * (x[along[c][0]] - x[c]).cross(x[along[c][1]] - x[c]).dot(x[along[c][2]] - x[c]);
}

/// The current model's worst hexahedron: the smallest corner Jacobian of any hexahedron relative
/// to the mean of its eight (1 for a parallelepiped, <= 0 for a folded element).
double
worst_corner_jacobian();

/// Writes the current model's mesh (.msh 4.1 ASCII) through a temporary file and a rename.
void
write_mesh_atomically(const std::string &path);

/// gmsh's version ("4.8.4").
std::string
gmsh_version();

/// Writes text through a temporary file and a rename.
void
write_text_atomically(const std::string &path, const std::string &text);

/// Implementation of with_gmsh (kept out of the template to hide gmsh.h).
void
rethrow_gmsh_error(const std::string &what);

template <class F>
void
with_gmsh(const std::string &what, F &&f)
{
  GmshSession session;
  try
    {
      f();
    }
  catch (...)
    {
      rethrow_gmsh_error(what);
    }
}
} // namespace gearkit
