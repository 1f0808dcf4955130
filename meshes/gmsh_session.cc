#include "meshes/gmsh_session.h"

#include "geometry/types.h"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <limits>
#include <vector>

namespace gearkit
{
GmshSession::GmshSession()
{
  gmsh::initialize();
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::option::setNumber("General.Verbosity", 1);
}

GmshSession::~GmshSession() { gmsh::finalize(); }

void
rethrow_gmsh_error(const std::string &what)
{
  try
    {
      throw;
    }
  catch (const InputError &)
    {
      throw;
    }
  catch (...)
    {
      std::string error;
      gmsh::logger::getLastError(error);
      throw InputError(what + ": gmsh failed (" + error + ")");
    }
}

std::pair<std::size_t, std::size_t>
require_hexahedra(const std::string &what)
{
  std::vector<int> types;
  gmsh::model::mesh::getElementTypes(types, 3);
  for (int t : types)
    if (t != 5)
      throw InputError(what + ": gmsh left non-hexahedral elements (type " + std::to_string(t) +
                       "); try other element sizes");
  std::vector<std::size_t> tags, node_tags, nodes;
  gmsh::model::mesh::getElementsByType(5, tags, node_tags);
  std::vector<double> coords, parametric;
  gmsh::model::mesh::getNodes(nodes, coords, parametric);
  return {tags.size(), nodes.size()};
}

std::string
gmsh_version()
{
  GmshSession session;
  std::string version;
  gmsh::option::getString("General.Version", version);
  return version;
}

double
worst_corner_jacobian()
{
  std::vector<std::size_t> nodes;
  std::vector<double>      xyz, parametric;
  gmsh::model::mesh::getNodes(nodes, xyz, parametric);
  std::vector<std::size_t> index; // node tag -> position in xyz
  for (std::size_t i = 0; i < nodes.size(); ++i)
    {
      if (nodes[i] >= index.size())
        index.resize(nodes[i] + 1);
      index[nodes[i]] = i;
    }
  std::vector<std::size_t> tags, corners;
  gmsh::model::mesh::getElementsByType(5, tags, corners);
  double worst = std::numeric_limits<double>::infinity();
  for (std::size_t e = 0; e < tags.size(); ++e)
    {
      Vec3 x[8];
      for (int c = 0; c < 8; ++c)
        {
          const std::size_t i = index[corners[8 * e + std::size_t(c)]];
          x[c]                = Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
        }
      double j[8], mean = 0;
      for (int c = 0; c < 8; ++c)
        mean += std::abs(j[c] = hexahedron_corner_jacobian(x, c)) / 8;
      for (double jc : j)
        worst = std::min(worst, jc / mean);
    }
  return worst;
}

void
write_mesh_atomically(const std::string &path)
{
  gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
  gmsh::option::setNumber("Mesh.Binary", 0);
  const std::string tmp = path + ".tmp.msh";
  gmsh::write(tmp);
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
    {
      std::remove(tmp.c_str());
      throw InputError("cannot write the mesh file " + path);
    }
}

void
write_text_atomically(const std::string &path, const std::string &text)
{
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << text;
    if (!out.flush())
      {
        std::remove(tmp.c_str());
        throw InputError("cannot write " + path);
      }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
    {
      std::remove(tmp.c_str());
      throw InputError("cannot write " + path);
    }
}
} // namespace gearkit
