// Segment meshes read back through gmsh for the mesh tests (a second, independent path from the
// writers' bookkeeping), and the trilinear hexahedron's volume and corner Jacobians.
#pragma once

#include "geometry/types.h"

#include <Eigen/Dense>
#include <gmsh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace gearkit::test_data
{
struct MeshFile
{
  std::map<int, std::vector<std::size_t>> group_nodes; ///< physical surface id -> node tags
  std::map<int, std::vector<std::array<std::size_t, 4>>> group_quads; ///< id -> quadrilaterals
  std::map<std::size_t, Vec3>                            nodes;
  std::vector<std::array<std::size_t, 8>>                hexahedra;
  std::set<int>                                          other_element_types;
};

/// Reads the mesh back through gmsh (a second, independent path from the writer's bookkeeping).
inline MeshFile
read(const std::string &path)
{
  MeshFile m;
  gmsh::initialize();
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::open(path);
  std::vector<std::size_t> tags;
  std::vector<double>      xyz, par;
  gmsh::model::mesh::getNodes(tags, xyz, par);
  for (std::size_t i = 0; i < tags.size(); ++i)
    m.nodes[tags[i]] = Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  std::vector<int>                      types;
  std::vector<std::vector<std::size_t>> element_tags, element_nodes;
  gmsh::model::mesh::getElements(types, element_tags, element_nodes, 3);
  for (std::size_t t = 0; t < types.size(); ++t)
    {
      if (types[t] != 5)
        {
          m.other_element_types.insert(types[t]);
          continue;
        }
      for (std::size_t e = 0; e < element_tags[t].size(); ++e)
        {
          std::array<std::size_t, 8> h;
          std::copy_n(element_nodes[t].begin() + 8 * e, 8, h.begin());
          m.hexahedra.push_back(h);
        }
    }
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, 2);
  for (const auto &[dim, id] : groups)
    {
      std::vector<double> coords;
      gmsh::model::mesh::getNodesForPhysicalGroup(dim, id, m.group_nodes[id], coords);
      std::vector<int> entities;
      gmsh::model::getEntitiesForPhysicalGroup(dim, id, entities);
      for (int e : entities)
        {
          std::vector<std::size_t> quads, quad_nodes;
          gmsh::model::mesh::getElementsByType(3, quads, quad_nodes, e);
          for (std::size_t q = 0; q < quads.size(); ++q)
            m.group_quads[id].push_back({quad_nodes[4 * q], quad_nodes[4 * q + 1],
                                         quad_nodes[4 * q + 2], quad_nodes[4 * q + 3]});
        }
    }
  gmsh::finalize();
  return m;
}

/// Volume of a trilinear hexahedron (2x2x2 Gauss) and its smallest corner Jacobian determinant
/// (gmsh node order: bottom 0-3, top 4-7, counter-clockwise).
inline std::pair<double, double>
hex_volume_and_min_jacobian(const std::array<Vec3, 8> &x)
{
  static const int s[8][3]  = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                               {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  auto             jacobian = [&](double a, double b, double c) {
    Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
    for (int k = 0; k < 8; ++k)
      {
        const Vec3 g(s[k][0] * (1 + s[k][1] * b) * (1 + s[k][2] * c),
                                 s[k][1] * (1 + s[k][0] * a) * (1 + s[k][2] * c),
                                 s[k][2] * (1 + s[k][0] * a) * (1 + s[k][1] * b));
        J += x[k] * g.transpose() / 8;
      }
    return J.determinant();
  };
  const double g      = 1 / std::sqrt(3.0);
  double       volume = 0, min_j = HUGE_VAL;
  for (int k = 0; k < 8; ++k)
    {
      volume += jacobian(s[k][0] * g, s[k][1] * g, s[k][2] * g);
      min_j = std::min(min_j, jacobian(s[k][0], s[k][1], s[k][2]));
    }
  return {volume, min_j};
}

/// The corner positions of one hexahedron of the mesh.
inline std::array<Vec3, 8>
hex_corners(const MeshFile &m, const std::array<std::size_t, 8> &h)
{
  std::array<Vec3, 8> x;
  for (int k = 0; k < 8; ++k)
    x[k] = m.nodes.at(h[k]);
  return x;
}

/// The mesh's volume and its hexahedra's smallest corner Jacobian.
inline std::pair<double, double>
volume_and_min_jacobian(const MeshFile &m)
{
  double volume = 0, min_j = HUGE_VAL;
  for (const auto &h : m.hexahedra)
    {
      const auto [v, j] = hex_volume_and_min_jacobian(hex_corners(m, h));
      volume += v, min_j = std::min(min_j, j);
    }
  return {volume, min_j};
}

} // namespace gearkit::test_data
