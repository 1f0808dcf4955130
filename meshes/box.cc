#include "meshes/box.h"

#include "meshes/gmsh_session.h"

#include <gmsh.h>

#include <sstream>

namespace gearkit
{
void
write_box_mesh(const Vec3 &size, int nx, int ny, int nz, const std::string &path)
{
  if (!(size.minCoeff() > 0 && nx >= 1 && ny >= 1 && nz >= 1))
    throw InputError("box mesh: needs positive sizes and at least one element per direction");
  with_gmsh("box mesh", [&] {
    namespace geo = gmsh::model::geo;
    gmsh::model::add("box");
    const int p0 = geo::addPoint(0, 0, 0), p1 = geo::addPoint(size.x(), 0, 0);
    const int p2 = geo::addPoint(size.x(), size.y(), 0), p3 = geo::addPoint(0, size.y(), 0);
    const int ly0 = geo::addLine(p0, p1), lx1 = geo::addLine(p1, p2);
    const int ly1 = geo::addLine(p2, p3), lx0 = geo::addLine(p3, p0);
    const int surface = geo::addPlaneSurface({geo::addCurveLoop({ly0, lx1, ly1, lx0})});
    for (int l : {ly0, ly1})
      geo::mesh::setTransfiniteCurve(l, nx + 1);
    for (int l : {lx0, lx1})
      geo::mesh::setTransfiniteCurve(l, ny + 1);
    geo::mesh::setTransfiniteSurface(surface);
    geo::mesh::setRecombine(2, surface);
    gmsh::vectorpair out;
    geo::extrude({{2, surface}}, 0, 0, size.z(), out, {nz}, {}, true);
    geo::synchronize();
    // lateral surfaces follow the loop: y = 0, x = Lx, y = Ly, x = 0
    const std::pair<int, const char *> groups[] = {{out[5].second, "x0"}, {out[3].second, "x1"},
                                                   {out[2].second, "y0"}, {out[4].second, "y1"},
                                                   {surface, "z0"},       {out[0].second, "z1"}};
    for (int id = 1; id <= 6; ++id)
      gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, {groups[id - 1].first}, id),
                                   groups[id - 1].second);
    gmsh::model::setPhysicalName(3, gmsh::model::addPhysicalGroup(3, {out[1].second}, 1), "body");
    gmsh::model::mesh::generate(3);
    require_hexahedra("box mesh");
    write_mesh_atomically(path);
  });
  std::ostringstream json;
  json.precision(12);
  json << "{\n  \"gear\": \"box\",\n  \"analytic_volume\": " << size.prod()
       << ",\n  \"physical_surfaces\": {\"x0\": 1, \"x1\": 2, \"y0\": 3, \"y1\": 4, \"z0\": 5, "
          "\"z1\": 6},\n  \"physical_volumes\": {\"body\": 1}\n}\n";
  write_text_atomically(path + ".json", json.str());
}
} // namespace gearkit
