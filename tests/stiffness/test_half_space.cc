// Half-space influence functions and the contact solver against exact Hertz solutions: point
// contact (approach, contact radius, peak pressure) and the FZG C14 line contact at the pitch
// point (reference-data.md section 5).
#include "geometry/involute_gear.h"
#include "stiffness/contact_solver.h"
#include "stiffness/half_space.h"
#include "tests/fzg_c_pair.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

using namespace gearkit;

TEST(HalfSpace, RectangleAgainstQuadratureAndFarField)
{
  const double E = 2.3e11, a = 0.4e-3, b = 1.1e-3, F = 7.0;
  // outside the rectangle: brute-force midpoint quadrature of p / (pi E) integral of dA / r
  for (const auto &[x, y] : {std::pair{1.3e-3, 0.2e-3}, std::pair{-0.5e-3, 1.6e-3}})
    {
      const int n   = 800;
      double    sum = 0;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
          {
            const double xs = -a + 2 * a * (i + 0.5) / n, ys = -b + 2 * b * (j + 0.5) / n;
            sum += 1 / std::hypot(x - xs, y - ys);
          }
      const double quadrature = F / (4 * a * b) / (pi * E) * sum * (2 * a / n) * (2 * b / n);
      EXPECT_NEAR(rectangle_displacement(x, y, a, b, F, E) / quadrature, 1, 1e-5);
    }
  // centre of a square: p / (pi E) 8 a asinh(1) (Johnson 3.25); far away: a point force
  EXPECT_NEAR(rectangle_displacement(0, 0, a, a, F, E),
              F / (4 * a * a) / (pi * E) * 8 * a * std::asinh(1.0), 1e-15);
  const double r = 5;
  EXPECT_NEAR(rectangle_displacement(r, 0, a, b, F, E) / (F / (pi * E * r)), 1, 1e-6);
  // no loss of digits far along the long side
  EXPECT_NEAR(rectangle_displacement(0, r, a, b, F, E) / (F / (pi * E * r)), 1, 1e-6);
  // Boussinesq at the surface equals the same point force
  const Material steel{E, 0.3};
  EXPECT_NEAR(point_load_displacement(r, 0, F, steel) / (F * (1 - 0.09) / (pi * E * r)), 1, 1e-12);
}

namespace
{
/// Cells of size hx x hy centred on a grid, gap from a function, lever 1, compliance from the
/// rectangle solution with the pair's E*.
struct Grid
{
  int                 nx, ny;
  double              hx, hy;
  std::vector<double> x, y;
};

ContactProblem
half_space_problem(const Grid &g, double modulus, double load,
                   const std::function<double(double, double)> &gap)
{
  const int      n = g.nx * g.ny;
  ContactProblem p;
  p.compliance.resize(n, n);
  p.gap.resize(n);
  p.lever = Eigen::VectorXd::Ones(n);
  p.load  = load;
  for (int i = 0; i < n; ++i)
    {
      p.gap[i] = gap(g.x[i / g.ny], g.y[i % g.ny]);
      for (int j = 0; j < n; ++j)
        p.compliance(j, i) =
            rectangle_displacement(g.x[j / g.ny] - g.x[i / g.ny], g.y[j % g.ny] - g.y[i % g.ny],
                                   g.hx / 2, g.hy / 2, 1.0, modulus);
    }
  return p;
}

Grid
grid(int nx, double x0, double x1, int ny, double y0, double y1)
{
  Grid g{nx, ny, (x1 - x0) / nx, (y1 - y0) / ny, {}, {}};
  for (int i = 0; i < nx; ++i)
    g.x.push_back(x0 + (i + 0.5) * g.hx);
  for (int j = 0; j < ny; ++j)
    g.y.push_back(y0 + (j + 0.5) * g.hy);
  return g;
}
} // namespace

TEST(ContactSolver, HertzPointContact)
{
  // Sphere R on a flat, both steel: a = (3 P R / 4 E*)^(1/3), delta = a^2 / R, p0 = 3 P / (2 pi
  // a^2).
  const Material steel{210e9, 0.3};
  const double   Es = contact_modulus(steel, steel), R = 20e-3, P = 500;
  const double   a = std::cbrt(3 * P * R / (4 * Es)), delta = a * a / R,
               p0         = 3 * P / (2 * pi * a * a);
  const Grid            g = grid(31, -1.55 * a, 1.55 * a, 31, -1.55 * a, 1.55 * a);
  const ContactSolution s = solve_contact(
      half_space_problem(g, Es, P, [&](double x, double y) { return (x * x + y * y) / (2 * R); }));
  EXPECT_NEAR(s.force.sum(), P, 1e-9 * P);
  EXPECT_NEAR(s.approach / delta, 1, 0.01);
  const double area = s.active * g.hx * g.hy;
  EXPECT_NEAR(std::sqrt(area / pi) / a, 1, 0.03);
  EXPECT_NEAR(s.force.maxCoeff() / (g.hx * g.hy) / p0, 1, 0.02);
  EXPECT_LT(s.penetration, 1e-12);
  EXPECT_GE(s.force.minCoeff(), 0);
}

TEST(ContactSolver, HertzLineContactFzgC14PitchPoint)
{
  // FZG C14 at the pitch point: F_bt 5912 N over b = 14 mm; the relative radius from the gear
  // geometry. Published p0 = 1347 MPa (reference-data.md section 5). The half-width that goes
  // with it, a = 2 F / (pi p0 b), is 199.6 um: the 99.8 um listed there is exactly half of it and
  // does not satisfy the listed formulas with the listed F and p0.
  const auto [pd, gd] = test_data::fzg_c_pair();
  const auto   pinion = InvoluteGear::create(pd), gear = InvoluteGear::create(gd);
  const double alpha = working_pressure_angle(*pinion, *gear);
  const double R1 = pinion->base_radius * std::tan(alpha), R2 = gear->base_radius * std::tan(alpha);
  const double R = 1 / (1 / R1 + 1 / R2);
  const Material steel{206e9, 0.3};
  const double   Es = contact_modulus(steel, steel), F = 5912, L = 14e-3;
  auto half_width = [&](double q) { return std::sqrt(4 * q * R / (pi * Es)); }; // q: load / length
  auto peak       = [&](double q) { return 2 * q / (pi * half_width(q)); };
  EXPECT_NEAR(peak(F / L), 1347e6, 0.01 * 1347e6);
  EXPECT_NEAR(half_width(F / L), 2 * F / (pi * 1347e6 * L), 0.01 * half_width(F / L));

  // Finite-length line contact on the half-space: the square ends carry more than the mean (the
  // half-space has no end), and in the middle of the face the strip is Hertzian for its own
  // load per length q: peak 2 q / (pi a(q)), width 2 a(q).
  const double          a = half_width(F / L);
  const Grid            g = grid(24, -1.2 * a, 1.2 * a, 28, -L / 2, L / 2);
  const ContactSolution s = solve_contact(
      half_space_problem(g, Es, F, [&](double x, double) { return x * x / (2 * R); }));
  EXPECT_NEAR(s.force.sum(), F, 1e-9 * F);
  auto strip = [&](int j, double &q, double &p, int &cells) {
    q = p = 0, cells = 0;
    for (int i = 0; i < g.nx; ++i)
      {
        const double f = s.force[i * g.ny + j];
        q += f / g.hy, p = std::max(p, f / (g.hx * g.hy)), cells += f > 0;
      }
  };
  double q_mid, p_mid, q_end, p_end;
  int    w_mid, w_end;
  strip(g.ny / 2, q_mid, p_mid, w_mid);
  strip(0, q_end, p_end, w_end);
  EXPECT_GT(q_end, q_mid);
  EXPECT_LT(q_mid, F / L);
  EXPECT_NEAR(p_mid / peak(q_mid), 1, 0.02);
  EXPECT_NEAR(w_mid * g.hx / (2 * half_width(q_mid)), 1, 0.1); // within a cell
}

TEST(ContactSolver, ZeroLoadAndBadInput)
{
  ContactProblem p;
  p.compliance            = Eigen::MatrixXd::Identity(3, 3) * 1e-9;
  p.gap                   = Eigen::Vector3d(2e-6, 1e-6, 3e-6);
  p.lever                 = Eigen::Vector3d(1, 0.5, 1);
  p.load                  = 0;
  const ContactSolution s = solve_contact(p);
  EXPECT_EQ(s.force.norm(), 0);
  EXPECT_NEAR(s.approach, 2e-6, 1e-18); // first touch: min g / lambda
  p.load = -1;
  EXPECT_THROW(solve_contact(p), InputError);
  p.load  = 1;
  p.lever = Eigen::Vector3d(1, 0, 1);
  EXPECT_THROW(solve_contact(p), InputError);
  p.lever = Eigen::Vector2d(1, 1);
  EXPECT_THROW(solve_contact(p), InputError);
}

namespace
{
/// div sigma of a field given by its gradient at points, by central differences [N/m^3].
template <typename GradientOf>
Vec3
divergence_of_stress(const GradientOf &gradient_at, const Vec3 &x, const Material &m, double h)
{
  Vec3 div = Vec3::Zero();
  for (int j = 0; j < 3; ++j)
    {
      const Vec3 e = h * Vec3::Unit(j);
      div += (stress(gradient_at(x + e), m) - stress(gradient_at(x - e), m)).col(j) / (2 * h);
    }
  return div;
}
} // namespace

TEST(HalfSpace, PointForceFieldIsBoussinesqs)
{
  // a tilted half-space: load at x0 pushing along d; the field in equilibrium everywhere
  // inside, free of traction on the surface, u_z and u_r at the surface as Johnson 3.21, its
  // gradient the derivative of u
  const Material m{2.07e11, 0.29};
  const Vec3     x0(1e-3, -2e-3, 0.5e-3), d = Vec3(0.3, -0.4, 0.87).normalized();
  const double   F  = 3.0;
  auto           at = [&](const Vec3 &x) { return point_force_field(x, x0, d, F, m); };
  const Vec3     t1 = d.unitOrthogonal(), t2 = d.cross(t1);
  const double   G = m.youngs_modulus / (2 * (1 + m.poisson_ratio));
  for (const Vec3 &offset : {Vec3(0.7e-3 * t1 + 0.4e-3 * d), Vec3(-0.3e-3 * t2 + 1.5e-3 * d),
                             Vec3(2e-3 * t1 - 1e-3 * t2 + 0.2e-3 * d)})
    {
      const Vec3              x = x0 + offset;
      const DisplacementField f = at(x);
      const double            h = 1e-7;
      Eigen::Matrix3d         fd;
      for (int j = 0; j < 3; ++j)
        fd.col(j) = (at(x + h * Vec3::Unit(j)).u - at(x - h * Vec3::Unit(j)).u) / (2 * h);
      EXPECT_LT((fd - f.gradient).norm(), 1e-7 * f.gradient.norm());
      const Vec3 div =
          divergence_of_stress([&](const Vec3 &y) { return at(y).gradient; }, x, m, 1e-7);
      EXPECT_LT(div.norm() * offset.norm(), 1e-6 * stress(f.gradient, m).norm());
    }
  for (const double r : {0.1e-3, 1e-3, 7e-3})
    {
      const Vec3              x = x0 + r * (0.6 * t1 + 0.8 * t2);
      const DisplacementField f = at(x);
      EXPECT_LT((stress(f.gradient, m) * d).norm(), 1e-9 * stress(f.gradient, m).norm());
      EXPECT_NEAR(f.u.dot(d) / point_load_displacement(r, 0, F, m), 1, 1e-12);
      // u_r = -(1 - 2 nu) F / (4 pi G r): the surface moves toward the load
      EXPECT_NEAR(f.u.dot(0.6 * t1 + 0.8 * t2) /
                      (-(1 - 2 * m.poisson_ratio) * F / (4 * pi * G * r)),
                  1, 1e-12);
    }
}

TEST(HalfSpace, CutOffNearFieldBodyForceAndTraction)
{
  // chi u with a quintic cut-off: the body force div sigma(chi u) against central differences
  // of sigma(chi u); 1 and 0 inside and outside; the traction sigma(chi u) n by definition
  const Material m{2.1e11, 0.3};
  const Vec3     x0 = Vec3::Zero(), d = Vec3::UnitZ();
  const double   r1 = 1e-3, r2 = 2.5e-3;
  auto           grad_chi_u = [&](const Vec3 &x) {
    const DisplacementField f = point_force_field(x, x0, d, 1.0, m);
    const Cutoff            c = radial_cutoff(x, x0, r1, r2);
    return Eigen::Matrix3d(c.value * f.gradient + f.u * c.gradient.transpose());
  };
  for (const Vec3 &x :
       {Vec3(1.2e-3, 0.3e-3, 0.5e-3), Vec3(-0.4e-3, 1.1e-3, 1.6e-3), Vec3(0.2e-3, -0.1e-3, 2.2e-3)})
    {
      const DisplacementField f    = point_force_field(x, x0, d, 1.0, m);
      const Cutoff            c    = radial_cutoff(x, x0, r1, r2);
      const NearField         near = cut_off_near_field(f, c, d, m);
      const Vec3              fd   = divergence_of_stress(grad_chi_u, x, m, 1e-8);
      EXPECT_LT((near.body - fd).norm(), 1e-5 * near.body.norm()) << x.transpose();
      EXPECT_LT((near.traction - stress(grad_chi_u(x), m) * d).norm(),
                1e-12 * near.traction.norm());
    }
  EXPECT_EQ(radial_cutoff(Vec3(0.9e-3, 0, 0), x0, r1, r2).value, 1);
  EXPECT_EQ(radial_cutoff(Vec3(0, 0, 2.6e-3), x0, r1, r2).value, 0);
  EXPECT_NEAR(radial_cutoff(Vec3(0, 1.75e-3, 0), x0, r1, r2).value, 0.5, 1e-15);
  // inside the inner radius the field is Boussinesq's own: no body force
  const Vec3 x(0.3e-3, 0.2e-3, 0.4e-3);
  EXPECT_EQ(
      cut_off_near_field(point_force_field(x, x0, d, 1.0, m), radial_cutoff(x, x0, r1, r2), d, m)
          .body.norm(),
      0);
}

TEST(HalfSpace, CutOffStepResolvedToItsEnds)
{
  // Just inside either end of the step the cut-off still varies (its body force is small, not
  // zero): varies() says so from where x lies, while the value rounds to 1 near the inner end;
  // near the outer end the value is the tiny positive 10 t^3 (t = (outer - r) / w), not 1 less
  // almost 1 (rounding noise of either sign, which once made a quadrature point next to the
  // outer sphere count or not with the last bit of its coordinates).
  const Vec3   x0 = Vec3::Zero();
  const double r1 = 1e-3, r2 = 2e-3, w = r2 - r1;
  // s and t of the point as stored (r2 - x and x - r1 are exact next to either end)
  const auto value = [&](double x) {
    const double t = (r2 - x) / w;
    return t * t * t * (10 - 15 * t + 6 * t * t);
  };
  const auto slope = [&](double x) {
    const double s = (x - r1) / w, t = (r2 - x) / w;
    return -30 * s * s * t * t / w;
  };
  for (const double t : {1e-3, 1e-5, 1e-6, 1e-7})
    {
      const double x     = r2 - t * w;
      const Cutoff outer = radial_cutoff(Vec3(x, 0, 0), x0, r1, r2);
      EXPECT_TRUE(outer.varies()) << t;
      EXPECT_GT(outer.value, 0) << t;
      EXPECT_NEAR(outer.value, value(x), 1e-12 * value(x)) << t; // to its last digits
      EXPECT_NEAR(outer.gradient.x(), slope(x), 1e-12 * std::abs(slope(x))) << t;
      const double y     = r1 + t * w;
      const Cutoff inner = radial_cutoff(Vec3(0, 0, y), x0, r1, r2);
      EXPECT_TRUE(inner.varies()) << t;
      EXPECT_NEAR(inner.gradient.z(), slope(y), 1e-12 * std::abs(slope(y))) << t;
    }
  EXPECT_FALSE(radial_cutoff(Vec3(0.99e-3, 0, 0), x0, r1, r2).varies());
  EXPECT_FALSE(radial_cutoff(Vec3(0, 2e-3, 0), x0, r1, r2).varies());
  EXPECT_FALSE(radial_cutoff(Vec3(0, 3e-3, 0), x0, r1, r2).varies());
  // the elevation step alike, and the product of both constant where either is 0
  const Vec3 d = Vec3::UnitZ();
  EXPECT_TRUE(near_field_cutoff(Vec3(1e-3, 0, -1e-3), x0, d, r1 * 2, r2 * 2).varies());  // 45 deg
  EXPECT_FALSE(near_field_cutoff(Vec3(1e-4, 0, -1e-3), x0, d, r1 * 2, r2 * 2).varies()); // 84 deg
  EXPECT_FALSE(near_field_cutoff(Vec3(1e-3, 0, 1e-3), x0, d, r1 * 2, r2 * 2).varies());  // below
}

TEST(HalfSpace, ElevationCutOffKeepsTheFieldOffTheRayOppositeTheForce)
{
  // The near field's cut-off also by elevation above the load's tangent plane: 1 below it and
  // up to 30 degrees above, 0 from 60 degrees (the ray opposite the force, where Boussinesq's
  // field is singular, and all within 30 degrees of it), half at sin = (sin 30 + sin 60) / 2;
  // gradient and Hessian against central differences; the product with the radial cut-off's
  // body force div sigma(chi u) against central differences where both vary.
  const Material m{2.1e11, 0.3};
  const Vec3     x0(1e-3, -2e-3, 0.5e-3), d = Vec3(0.3, -0.2, 1).normalized();
  const Vec3     e1 = d.unitOrthogonal(), e2 = d.cross(e1);
  auto           at = [&](double r, double elevation, double azimuth) { // elevation above the plane
    return Vec3(x0 + r * (std::cos(elevation) * (std::cos(azimuth) * e1 + std::sin(azimuth) * e2) -
                          std::sin(elevation) * d));
  };
  auto psi = [&](const Vec3 &x) { return elevation_cutoff(x, x0, d, pi / 6, pi / 3); };
  EXPECT_EQ(psi(at(2e-3, -pi / 4, 0.3)).value, 1);       // in the body
  EXPECT_EQ(psi(at(2e-3, 0.9 * pi / 6, 1.1)).value, 1);  // just above the plane
  EXPECT_EQ(psi(at(2e-3, 1.01 * pi / 3, 2.0)).value, 0); // near the ray
  EXPECT_EQ(psi(at(2e-3, pi / 2, 0)).value, 0);          // on it
  EXPECT_EQ(psi(x0).value, 1);
  EXPECT_NEAR(psi(at(2e-3, std::asin((0.5 + std::sqrt(0.75)) / 2), 0.7)).value, 0.5, 1e-14);
  for (const Vec3 &x : {at(1.5e-3, 0.6, 0.2), at(3e-3, 0.8, -2.0), at(0.4e-3, 0.95, 1.3)})
    {
      const Cutoff c = psi(x);
      ASSERT_GT(c.value, 0);
      ASSERT_LT(c.value, 1);
      const double h = 1e-9;
      for (int j = 0; j < 3; ++j)
        {
          const Vec3   e  = h * Vec3::Unit(j);
          const double fd = (psi(x + e).value - psi(x - e).value) / (2 * h);
          EXPECT_NEAR(c.gradient[j], fd, 1e-6 * c.gradient.norm()) << j;
          const Vec3 hd = (psi(x + e).gradient - psi(x - e).gradient) / (2 * h);
          EXPECT_LT((c.hessian.col(j) - hd).norm(), 1e-5 * c.hessian.norm()) << j;
        }
    }
  // the near field's cut-off: radial 1-2.5 mm times elevation 30-60 degrees
  const double r1 = 1e-3, r2 = 2.5e-3;
  EXPECT_EQ(near_field_cutoff(at(2e-3, pi / 2, 0), x0, d, r1, r2).value, 0);
  EXPECT_EQ(near_field_cutoff(at(0.5e-3, 0.2, 0), x0, d, r1, r2).value, 1);
  EXPECT_EQ(near_field_cutoff(at(3e-3, 0.2, 0), x0, d, r1, r2).value, 0);
  auto grad_chi_u = [&](const Vec3 &x) {
    const DisplacementField f = point_force_field(x, x0, d, 1.0, m);
    const Cutoff            c = near_field_cutoff(x, x0, d, r1, r2);
    return Eigen::Matrix3d(c.value * f.gradient + f.u * c.gradient.transpose());
  };
  for (const Vec3 &x : {at(1.8e-3, 0.7, 0.4), at(0.6e-3, 0.8, -1.0), at(2.2e-3, 0.9, 2.5)})
    {
      const Cutoff c = near_field_cutoff(x, x0, d, r1, r2);
      ASSERT_GT(c.value, 0);
      ASSERT_LT(c.value, 1);
      const NearField near = cut_off_near_field(point_force_field(x, x0, d, 1.0, m), c, d, m);
      const Vec3      fd   = divergence_of_stress(grad_chi_u, x, m, 1e-8);
      EXPECT_LT((near.body - fd).norm(), 1e-5 * near.body.norm()) << x.transpose();
    }
}
