#include "tca/unloaded_tca.h"

#include "base/tooth_pairs.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <tuple>

namespace gearkit
{
namespace
{
double
wrap(double a) // to (-pi, pi]
{
  return a - 2 * pi * std::floor((a + pi) / (2 * pi));
}

Eigen::Matrix3d
rot_z(double a)
{
  return Eigen::AngleAxisd(a, Vec3::UnitZ()).toRotationMatrix();
}
} // namespace

UnloadedTca::UnloadedTca(std::shared_ptr<const MemberFlanks> p,
                         std::shared_ptr<const MemberFlanks> g, double a, const Misalignment &m,
                         const TcaOptions &o)
    : UnloadedTca(p, g, Assembly(a, g->teeth(), m), o)
{
}

UnloadedTca::UnloadedTca(std::shared_ptr<const MemberFlanks> p,
                         std::shared_ptr<const MemberFlanks> g, const Assembly &a,
                         const TcaOptions &o)
    : pinion(std::move(p))
    , gear(std::move(g))
    , assembly(a)
    , options(o)
    , ratio(double(pinion->teeth()) / gear->teeth())
{
  if (options.positions_per_mesh < 1 || options.mesh_cycles < 1 || options.profile_samples < 2 ||
      options.face_samples < 2)
    throw InputError("unloaded TCA: positions per mesh, mesh cycles (>= 1) and search samples "
                     "(>= 2) must be positive");
  if (!(options.contact_tolerance >= 0))
    throw InputError("unloaded TCA: the contact tolerance must be >= 0 [m]");
  if (options.contact_tolerance == 0)
    {
      // the transverse module 2 r / z from the radius of the middle of a pinion flank
      const Flank      &f = pinion->flank(0, options.side);
      const FlankDomain d = f.domain();
      double            r = 0;
      try
        {
          r = f.evaluate((d.u_min + d.u_max) / 2, (d.v_min + d.v_max) / 2)
                  .position.head<2>()
                  .norm();
        }
      catch (const InputError &)
        {
        }
      options.contact_tolerance = r > 0 ? 3e-7 * 2 * r / pinion->teeth() : 1e-9;
    }
}

namespace
{
std::shared_ptr<const MemberFlanks>
checked_pinion(const std::shared_ptr<const InvoluteGear> &p,
               const std::shared_ptr<const InvoluteGear> &g)
{
  const auto &d1 = p->data(), &d2 = g->data();
  if (const std::string why = external_pair_mismatch(d1, d2); !why.empty())
    throw InputError("unloaded TCA: " + d1.name + " and " + d2.name + " cannot mesh: they " + why);
  return std::make_shared<InvoluteMemberFlanks>(p);
}
} // namespace

UnloadedTca::UnloadedTca(std::shared_ptr<const InvoluteGear> p,
                         std::shared_ptr<const InvoluteGear> g, double a, const Misalignment &m,
                         const TcaOptions &o)
    : UnloadedTca(checked_pinion(p, g), std::make_shared<InvoluteMemberFlanks>(g), a, m, o)
{
}

bool
UnloadedTca::touch_angle(int j, const Vec3 &X, double expected, double &psi, double &u2,
                         double &v2) const
{
  return solve_touch(j, X, expected, psi, u2, v2) == Touch::on_flank;
}

UnloadedTca::Touch
UnloadedTca::solve_touch(int j, const Vec3 &X, double expected, double &psi, double &u2,
                         double &v2) const
{
  // Solve r_g(u2, v2) = Rz(psi) Q for (u2, v2, psi) by Newton, from the coarse flank sample
  // nearest in the rotation-invariant (radius, z) and the polar angle difference.
  const Flank      &flank = gear->flank(j, options.side);
  const FlankDomain d     = flank.domain();
  const Vec3        Q     = assembly.global_to_gear_unrotated(X);
  std::tie(u2, v2)        = gear->guess(j, options.side, Q.head<2>().norm(), Q.z());
  const Vec3 r0           = flank.evaluate(u2, v2).position;
  psi = expected + wrap(std::atan2(r0.y(), r0.x()) - std::atan2(Q.y(), Q.x()) - expected);
  // Converged when the points coincide to 1e-12 of the point's radius (0.05 pm at 50 mm, well
  // above the coordinates' rounding; relative, so that a gear and its scaled copy converge
  // alike); a start that Newton cannot bring there is no touch, nor one whose steps leave
  // the surface the flank continues to (a generated flank exists only where its cutter reaches:
  // evaluate throws beyond).
  bool converged = false;
  for (int it = 0; it < 40 && !converged; ++it)
    {
      FlankPoint f;
      try
        {
          f = flank.evaluate(u2, v2);
        }
      catch (const InputError &)
        {
          return Touch::none;
        }
      const Vec3 RQ = rot_z(psi) * Q;
      const Vec3 F  = f.position - RQ;
      if (F.norm() < 1e-12 * Q.norm())
        {
          converged = true;
          break;
        }
      Eigen::Matrix3d J;
      J.col(0)        = f.d_du;
      J.col(1)        = f.d_dv;
      J.col(2)        = -Vec3::UnitZ().cross(RQ);
      const Vec3 step = J.partialPivLu().solve(-F);
      u2 += step.x();
      v2 += step.y();
      psi += step.z();
      if (!std::isfinite(psi + u2 + v2))
        return Touch::none;
    }
  if (!converged)
    return Touch::none;
  // The gear passes through X once per turn: the pass nearest the expected angle (a Newton step
  // across a near-singular Jacobian can land whole turns away).
  if (std::abs(psi - expected) > pi)
    psi = expected + wrap(psi - expected);
  const double tol_u = 1e-12 * (d.u_max - d.u_min), tol_v = 1e-12 * (d.v_max - d.v_min);
  if (!(u2 >= d.u_min - tol_u && u2 <= d.u_max + tol_u &&
        std::abs(wrap(psi - expected)) < pi / gear->teeth()))
    return Touch::none;
  if (!(v2 >= d.v_min - tol_v && v2 <= d.v_max + tol_v))
    return Touch::beyond_face;
  return flank.contains(u2, v2) ? Touch::on_flank : Touch::none;
}

/// pair_contact's search, one tooth pair at one pinion angle, in its phases: the touch angle
/// sampled over the pinion flank (sample, with face_end for a mate beyond the gear's face), the
/// starts of the pattern search (starts), the pattern search from them with its Newton jumps
/// along a ridge (maximum), and Newton on the touch angle's stationarity (pinned).
class UnloadedTca::ContactSearch
{
public:
  /// s * touch angle of a pinion flank point; -inf where the gear flank cannot reach it.
  struct Sample
  {
    double value = -HUGE_VAL, u1 = 0, v1 = 0, psi = 0, u2 = 0, v2 = 0;
    bool   face_end = false; ///< moved to the gear's face end (face_end below)
  };

  ContactSearch(const UnloadedTca &tca, int pinion_tooth, int gear_tooth, double phi)
      : tca(tca)
      , options(tca.options)
      , assembly(tca.assembly)
      , pinion_tooth(pinion_tooth)
      , gear_tooth(gear_tooth)
      , phi(phi)
      , s(options.side == FlankSide::drive ? 1.0 : -1.0)
      , flank(tca.pinion->flank(pinion_tooth, options.side))
      , d(flank.domain())
      , gear_flank(tca.gear->flank(gear_tooth, options.side))
      , dg(gear_flank.domain())
      , expected(tca.ratio * phi)
      , nu(options.profile_samples)
      , nv(options.face_samples)
      , hu0((d.u_max - d.u_min) / (nu - 1))
      , hv0((d.v_max - d.v_min) / (nv - 1))
  {
  }

  std::vector<Sample>
  starts(const PairContact *near);
  Sample
  maximum(const std::vector<Sample> &starts);
  /// maximum from one flank point with initial steps (du, dv).
  Sample
  maximum_from(double u1, double v1, double du, double dv);
  Sample
  pinned(Sample best, bool *converged = nullptr);
  void
  fill(PairContact &c, const Sample &best) const;

private:
  /// A pattern search's position and step sizes.
  struct Search
  {
    Sample at;
    double hu, hv;
  };

  bool
  face_end(double u1, double &v1, double &psi, double &u2, double &v2) const;
  Sample
  sample(double u1, double v1);
  /// t beats u; a sample moved to the gear's face end only by more than 1e-10 rad (a few pm at
  /// the flank): where the flanks touch along a line through the face end, the line's interior
  /// points are the contact (their tangency is pinned in pinned(); the face end's only to
  /// ~1e-7).
  static bool
  better(const Sample &t, const Sample &u)
  {
    auto rank = [](const Sample &x) {
      return x.face_end ? x.value - 1e-10 * (1 + std::abs(x.value)) : x.value;
    };
    return rank(t) > rank(u);
  }
  static bool
  at_edge(double x, double lo, double hi)
  {
    return x - lo < 1e-7 * (hi - lo) || hi - x < 1e-7 * (hi - lo);
  }
  bool
  gear_edge(const Sample &t) const
  {
    return at_edge(t.u2, dg.u_min, dg.u_max) || at_edge(t.v2, dg.v_min, dg.v_max);
  }
  Eigen::Vector2d
  gradient(const Sample &t, bool free_u, bool free_v) const;
  Eigen::Vector2d
  newton_step(const Sample &t, bool free_u, bool free_v, bool *found = nullptr);
  bool
  gains_inwards(const Sample &t, bool free_u, bool free_v) const;
  void
  jump(Search &x);
  void
  refine(Search &x, double until);
  /// Newton from a coarse maximum; where it does not converge, the pattern search to the end.
  Sample
  finish(Search &found);

  const UnloadedTca &tca;
  const TcaOptions  &options;
  const Assembly    &assembly;
  const int          pinion_tooth, gear_tooth;
  const double       phi;
  const double       s; ///< 1 on the drive flanks, -1 on the coast flanks
  const Flank       &flank;
  const FlankDomain  d;
  const Flank       &gear_flank;
  const FlankDomain  dg;
  const double       expected;     ///< the gear's rotation for conjugate flanks
  const int          nu, nv;       ///< the grid's samples over the flank
  const double       hu0, hv0;     ///< and its steps
  int                samples = 0;  ///< flank samples taken (options.most_samples bounds them)
  int                crawl   = 64; ///< moves at one step size before a Newton step (below)
};

// (robust_search) A pinion point whose mate lies beyond an end of the gear's face: moved
// along the pinion's face (v1, at fixed u1) to where the gear's face end meets it, by Newton
// on r_g(u2, v_end) = Rz(psi) Q(X(u1, v1)). The contact of a face end then lies on a line of
// samples at fixed u1 instead of a thin band the pattern search cannot follow (a modified
// helical pinion's face edge stands off its face plane by the modification times sin beta_b,
// beyond the gear's face).
bool
UnloadedTca::ContactSearch::face_end(double u1, double &v1, double &psi, double &u2,
                                     double &v2) const
{
  v2 = v2 > dg.v_max ? dg.v_max : dg.v_min;
  for (int it = 0; it < 40; ++it)
    {
      FlankPoint p, q;
      try // (a generated flank exists only where its cutter reaches, as in solve_touch)
        {
          p = flank.evaluate(u1, v1);
          q = gear_flank.evaluate(u2, v2);
        }
      catch (const InputError &)
        {
          return false;
        }
      const Vec3 Q  = assembly.global_to_gear_unrotated(assembly.pinion_to_global(p.position, phi));
      const Vec3 RQ = rot_z(psi) * Q;
      const Vec3 F  = q.position - RQ;
      if (F.norm() < 1e-12 * Q.norm())
        {
          psi                = expected + wrap(psi - expected);
          const double tol_u = 1e-12 * (dg.u_max - dg.u_min) + 1e-12 / q.d_du.norm();
          const double tol_v = 1e-12 * (d.v_max - d.v_min) + 1e-12 / p.d_dv.norm();
          if (!(u2 >= dg.u_min - tol_u && u2 <= dg.u_max + tol_u && v1 >= d.v_min - tol_v &&
                v1 <= d.v_max + tol_v && std::abs(wrap(psi - expected)) < pi / tca.gear->teeth()))
            return false;
          u2 = std::clamp(u2, dg.u_min, dg.u_max);
          v1 = std::clamp(v1, d.v_min, d.v_max);
          return flank.contains(u1, v1) && gear_flank.contains(u2, v2);
        }
      Eigen::Matrix3d J;
      J.col(0)        = q.d_du;
      J.col(1)        = -(rot_z(psi) * assembly.global_to_gear_unrotated_vector(
                                           assembly.pinion_vector_to_global(p.d_dv, phi)));
      J.col(2)        = -Vec3::UnitZ().cross(RQ);
      const Vec3 step = J.partialPivLu().solve(-F);
      u2 += step.x();
      v1 += step.y();
      psi += step.z();
      if (!std::isfinite(psi + u2 + v1))
        return false;
    }
  return false;
}

UnloadedTca::ContactSearch::Sample
UnloadedTca::ContactSearch::sample(double u1, double v1)
{
  if (++samples > options.most_samples)
    {
      std::ostringstream m;
      m << "unloaded TCA: the contact search of pinion tooth " << pinion_tooth
        << " with gear tooth " << gear_tooth << " at pinion angle " << phi << " rad took more than "
        << options.most_samples
        << " flank samples without converging; expected a touch angle with one maximum "
           "over the flank (flanks that are smooth, and mismatched for a localised bearing or "
           "conjugate)";
      throw InputError(m.str());
    }
  Sample out;
  out.u1 = std::clamp(u1, d.u_min, d.u_max);
  out.v1 = std::clamp(v1, d.v_min, d.v_max);
  if (!flank.contains(out.u1, out.v1))
    return out;
  const Vec3  X = assembly.pinion_to_global(flank.evaluate(out.u1, out.v1).position, phi);
  const Touch t = tca.solve_touch(gear_tooth, X, expected, out.psi, out.u2, out.v2);
  out.face_end  = t == Touch::beyond_face && options.robust_search;
  if (t == Touch::on_flank || (out.face_end && face_end(out.u1, out.v1, out.psi, out.u2, out.v2)))
    out.value = s * out.psi;
  return out;
}

// A grid over the flank, then a pattern search that halves its step around the best sample
// (it follows the maximum into corners and along edges as well as to interior maxima); with
// robust_search also around the grid's other local maxima and a nearby position's contact,
// the best result kept.
std::vector<UnloadedTca::ContactSearch::Sample>
UnloadedTca::ContactSearch::starts(const PairContact *near)
{
  std::vector<Sample> grid(nu * nv);
  Sample              best;
  for (int i = 0; i < nu; ++i)
    for (int l = 0; l < nv; ++l)
      {
        Sample &t = grid[i * nv + l];
        t         = sample(d.u_min + (d.u_max - d.u_min) * i / (nu - 1),
                           d.v_min + (d.v_max - d.v_min) * l / (nv - 1));
        if (better(t, best))
          best = t;
      }
  std::vector<Sample> starts{best};
  if (options.robust_search) // every local maximum of the grid (the best four) as well
    {
      std::vector<Sample> maxima;
      for (int i = 0; i < nu; ++i)
        for (int l = 0; l < nv; ++l)
          {
            const Sample &t     = grid[i * nv + l];
            bool          local = t.value > -HUGE_VAL;
            for (int a = -1; a <= 1 && local; ++a)
              for (int b = -1; b <= 1 && local; ++b)
                if ((a || b) && i + a >= 0 && i + a < nu && l + b >= 0 && l + b < nv)
                  local = !better(grid[(i + a) * nv + l + b], t);
            if (local)
              maxima.push_back(t);
          }
      std::sort(maxima.begin(), maxima.end(), better);
      for (std::size_t j = 0; j < maxima.size() && j < 4; ++j)
        if (maxima[j].u1 != best.u1 || maxima[j].v1 != best.v1)
          starts.push_back(maxima[j]);
    }
  if (near && near->found) // and a finer cluster around a nearby position's contact
    {
      Sample closest;
      for (int i = -2; i <= 2; ++i)
        for (int l = -2; l <= 2; ++l)
          {
            const Sample t = sample(near->u1 + i * hu0 / 4, near->v1 + l * hv0 / 4);
            if (better(t, closest))
              closest = t;
          }
      if (options.robust_search)
        starts.push_back(closest);
      else if (better(closest, starts[0]))
        starts[0] = closest;
    }
  return starts;
}

// The gradient of s psi in the free flank parameters follows from the implicit function
// theorem on r_g(u2, v2) = Rz(psi) Q(X(u1, v1)): d(u2, v2, psi) = J^-1 Rz(psi) dQ; the Newton
// step on its stationarity from differences of it (a pseudo-inverse handles line contact: a
// singular Hessian along the contact line).
Eigen::Vector2d
UnloadedTca::ContactSearch::gradient(const Sample &t, bool free_u, bool free_v) const
{
  const FlankPoint      p = flank.evaluate(t.u1, t.v1);
  const FlankPoint      q = gear_flank.evaluate(t.u2, t.v2);
  const Vec3            X = assembly.pinion_to_global(p.position, phi);
  const Vec3            Q = assembly.global_to_gear_unrotated(X);
  const Eigen::Matrix3d R = rot_z(t.psi);
  Eigen::Matrix3d       J;
  J.col(0)         = q.d_du;
  J.col(1)         = q.d_dv;
  J.col(2)         = -Vec3::UnitZ().cross(R * Q);
  const auto lu    = J.partialPivLu();
  auto       d_psi = [&](const Vec3 &dr) {
    const Vec3 dQ =
        assembly.global_to_gear_unrotated_vector(assembly.pinion_vector_to_global(dr, phi));
    return s * lu.solve(R * dQ).z();
  };
  return Eigen::Vector2d(free_u ? d_psi(p.d_du) : 0.0, free_v ? d_psi(p.d_dv) : 0.0);
}

// Whether a sample held at an edge of the pinion flank would gain, beyond the touch angle's
// rounding, by moving a millionth of the flank inwards: then the maximum lies inside, closer
// to the edge than the pattern search's step, and Newton along the edge has not found it.
bool
UnloadedTca::ContactSearch::gains_inwards(const Sample &t, bool free_u, bool free_v) const
{
  if (free_u && free_v)
    return false;
  const Eigen::Vector2d g  = gradient(t, true, true);
  const double          eu = 1e-6 * (d.u_max - d.u_min), ev = 1e-6 * (d.v_max - d.v_min);
  const double gain_u = free_u ? 0.0 : (t.u1 - d.u_min < d.u_max - t.u1 ? g.x() : -g.x()) * eu;
  const double gain_v = free_v ? 0.0 : (t.v1 - d.v_min < d.v_max - t.v1 ? g.y() : -g.y()) * ev;
  return std::max(gain_u, gain_v) > 1e-15 * (1 + std::abs(t.value));
}

// (`found`: whether the difference samples touch at all)
Eigen::Vector2d
UnloadedTca::ContactSearch::newton_step(const Sample &t, bool free_u, bool free_v, bool *found)
{
  const Eigen::Vector2d g0 = gradient(t, free_u, free_v);
  const double          eu = 1e-6 * (d.u_max - d.u_min), ev = 1e-6 * (d.v_max - d.v_min);
  Eigen::Matrix2d       H = Eigen::Matrix2d::Zero();
  for (int k = 0; k < 2; ++k)
    if (k == 0 ? free_u : free_v)
      {
        const Sample near = k == 0 ? sample(t.u1 + eu, t.v1) : sample(t.u1, t.v1 + ev);
        if (found && near.value == -HUGE_VAL)
          *found = false;
        H.col(k) = (gradient(near, free_u, free_v) - g0) / (k == 0 ? eu : ev);
      }
  // The Hessian from differences carries the gradient's rounding over the difference step
  // (~1e-10 of its largest eigenvalue): smaller eigenvalues are a contact line's flat direction,
  // in which Newton does not step.
  Eigen::CompleteOrthogonalDecomposition<Eigen::Matrix2d> cod(H);
  cod.setThreshold(1e-8);
  return Eigen::Vector2d(-cod.solve(g0));
}

// A search that keeps moving at one step size crawls along a ridge oblique to the flank
// parameters (near line contact): every `crawl` moves (64, 8 once a jump has gained) refine
// tries the Newton step of the touch angle's quadratic model, halved until it gains, which goes
// along the ridge at once (see pair()).
void
UnloadedTca::ContactSearch::jump(Search &x)
{
  const bool free_u = !at_edge(x.at.u1, d.u_min, d.u_max);
  const bool free_v = !at_edge(x.at.v1, d.v_min, d.v_max);
  if (!(free_u || free_v) || gear_edge(x.at) || x.at.face_end)
    return;
  bool            found = true;
  Eigen::Vector2d step;
  try // (a difference sample beyond where a generated gear flank exists: no step)
    {
      step = newton_step(x.at, free_u, free_v, &found);
    }
  catch (const InputError &)
    {
      return;
    }
  if (!found)
    return;
  for (int halvings = 0; halvings < 30 && step.allFinite(); ++halvings, step /= 2)
    {
      const Sample t = sample(x.at.u1 + step.x(), x.at.v1 + step.y());
      if (better(t, x.at))
        {
          x.at  = t;
          crawl = 8;
          return;
        }
    }
}

void
UnloadedTca::ContactSearch::refine(Search &x, double until)
{
  int moves = 0; // at this step size
  while ((x.hu > 1e-11 * (d.u_max - d.u_min) || x.hv > 1e-11 * (d.v_max - d.v_min)) &&
         x.hu > until * hu0)
    {
      Sample next = x.at;
      for (int a = -1; a <= 1; ++a)
        for (int b = -1; b <= 1; ++b)
          if (a || b)
            {
              const Sample t = sample(x.at.u1 + a * x.hu, x.at.v1 + b * x.hv);
              if (better(t, next))
                next = t;
            }
      // A move must gain more than the touch angle's rounding (1e-15 relative): along a
      // contact line the angle is flat to rounding, and a walk along a ridge of rounding
      // noise at steps of 1e-11 of the flank would take ~1e11 samples.
      const bool moved = !(next.u1 == x.at.u1 && next.v1 == x.at.v1);
      const bool gain  = moved && (next.value > x.at.value + 1e-15 * (1 + std::abs(x.at.value)) ||
                                  (x.at.value == -HUGE_VAL && next.value > -HUGE_VAL) ||
                                  next.face_end != x.at.face_end);
      if (!gain)
        {
          x.hu /= 2, x.hv /= 2, moves = 0;
          continue;
        }
      x.at = next;
      if (++moves % crawl == 0)
        jump(x);
      if (moves == 128) // a ridge too slanted for the jumps: on at a finer step (bounded work)
        x.hu /= 2, x.hv /= 2, moves = 0;
    }
}

// Each start coarsely (to 1e-4 of the grid step), the best of them kept; then Newton on the
// touch angle's stationarity pins an interior maximum to rounding (pinned), and where it does
// not converge (an edge, a kink of a modification, a face end) the pattern search goes on to
// the end, pinned again.
UnloadedTca::ContactSearch::Sample
UnloadedTca::ContactSearch::maximum(const std::vector<Sample> &starts)
{
  Search found{Sample(), hu0, hv0};
  for (const Sample &start : starts)
    if (start.value > -HUGE_VAL)
      {
        Search x{start, hu0, hv0};
        refine(x, 1e-4);
        if (better(x.at, found.at))
          found = x;
      }
  return finish(found);
}

UnloadedTca::ContactSearch::Sample
UnloadedTca::ContactSearch::maximum_from(double u1, double v1, double du, double dv)
{
  Search x{sample(u1, v1), du, dv};
  if (x.at.value == -HUGE_VAL)
    return x.at;
  refine(x, du / hu0 / 2); // one halving of the first step: Newton (finish) from there
  return finish(x);
}

UnloadedTca::ContactSearch::Sample
UnloadedTca::ContactSearch::finish(Search &found)
{
  if (found.at.value == -HUGE_VAL)
    return found.at;
  bool         converged = false;
  const Sample newton    = found.at.face_end ? found.at : pinned(found.at, &converged);
  if (converged)
    return newton;
  refine(found, 0);
  return pinned(found.at);
}

// Newton on the stationarity of the touch angle (the classical tangency condition) in the
// free parameters: the pattern search locates the maximum to ~1e-8 (the touch angle is flat
// there), Newton pins it to rounding.
UnloadedTca::ContactSearch::Sample
UnloadedTca::ContactSearch::pinned(Sample best, bool *converged)
{
  const bool free_u = !at_edge(best.u1, d.u_min, d.u_max);
  const bool free_v = !at_edge(best.v1, d.v_min, d.v_max);
  // With `converged` asked for, also where the mate lies on the gear flank's edge (a spur
  // pair's contact line ending at both faces): the step counts only where its difference
  // samples touch, and a stationary point reached through touching samples is the maximum.
  if ((free_u || free_v) && (converged || !gear_edge(best)))
    for (int it = 0; it < 8; ++it)
      {
        bool                  found = true;
        const Eigen::Vector2d step  = newton_step(best, free_u, free_v, &found);
        const Sample          next  = sample(best.u1 + step.x(), best.v1 + step.y());
        if (!found || !(next.value >= best.value - 1e-14))
          break;
        const bool done = step.norm() < 1e-13;
        best            = next;
        if (done)
          {
            if (converged)
              *converged = !best.face_end && !gains_inwards(best, free_u, free_v);
            break;
          }
      }
  return best;
}

void
UnloadedTca::ContactSearch::fill(PairContact &c, const Sample &best) const
{
  c.found       = true;
  c.touch_angle = best.psi;
  c.u1 = best.u1, c.v1 = best.v1, c.u2 = best.u2, c.v2 = best.v2;
  c.edge = at_edge(c.u1, d.u_min, d.u_max) || at_edge(c.v1, d.v_min, d.v_max) ||
           at_edge(c.u2, dg.u_min, dg.u_max) || at_edge(c.v2, dg.v_min, dg.v_max);
  set_contact_geometry(c, assembly, flank, gear_flank, phi, c.touch_angle);
  set_relative_curvature(c, assembly, flank, gear_flank, phi, c.touch_angle);
}

template <class Find>
PairContact
UnloadedTca::pair_contact(int k, double phi, Find &&find) const
{
  // Pair k: the k-th pinion tooth to pass the line of centres (tooth -k) and its mate.
  PairContact c;
  const bool  drive = options.side == FlankSide::drive;
  c.pinion_tooth    = mod(-k, pinion->teeth());
  c.gear_tooth      = mod(drive ? k - 1 : k, gear->teeth());
  if (!pinion->has(c.pinion_tooth, options.side) || !gear->has(c.gear_tooth, options.side))
    return c;
  ContactSearch               search(*this, c.pinion_tooth, c.gear_tooth, phi);
  const ContactSearch::Sample best = find(search);
  if (best.value == -HUGE_VAL) // the gear flank reaches no point of the pinion flank
    return c;
  search.fill(c, best);
  return c;
}

PairContact
UnloadedTca::pair(int k, double phi, const PairContact *near) const
{
  return pair_contact(
      k, phi, [near](ContactSearch &search) { return search.maximum(search.starts(near)); });
}

PairContact
UnloadedTca::pair_from(int k, double phi, double u1, double v1, double du, double dv) const
{
  if (!(du > 0) || !(dv > 0) || !std::isfinite(u1 + v1 + du + dv))
    throw InputError("unloaded TCA: a local contact search needs a finite flank point and "
                     "steps > 0");
  return pair_contact(k, phi,
                      [=](ContactSearch &search) { return search.maximum_from(u1, v1, du, dv); });
}

TcaPosition
UnloadedTca::at(double phi) const
{
  TcaPosition pos;
  pos.pinion_angle = phi;
  const int    k0  = int(std::lround(phi * pinion->teeth() / (2 * pi)));
  const double s   = options.side == FlankSide::drive ? 1.0 : -1.0;
  for (int k = k0 - 3; k <= k0 + 3; ++k)
    {
      PairContact c = pair(k, phi);
      if (!c.found)
        continue;
      pos.pairs.push_back(c);
      // The pair that touches first leads; among pairs touching together (conjugate flanks)
      // prefer one whose contact lies inside both flanks.
      const PairContact *lead = pos.leading < 0 ? nullptr : &pos.pairs[pos.leading];
      if (!lead || s * c.touch_angle > s * lead->touch_angle + 1e-14 ||
          (s * c.touch_angle > s * lead->touch_angle - 1e-14 && lead->edge && !c.edge))
        pos.leading = int(pos.pairs.size()) - 1;
    }
  if (pos.leading < 0)
    {
      std::ostringstream m;
      m << "unloaded TCA: no tooth pair meets at pinion angle " << phi
        << " rad; expected flanks that mesh (check the centre distance, hands and face widths)";
      throw InputError(m.str());
    }
  pos.gear_angle         = pos.pairs[pos.leading].touch_angle;
  pos.transmission_error = phi - pos.gear_angle / ratio;
  const Vec3 axis        = assembly.gear_axis();
  for (PairContact &c : pos.pairs)
    {
      // A gear rotation d psi moves the gear flank along its normal by |(a x r) . n| d psi.
      const Vec3 r = c.position - assembly.gear_centre();
      c.separation =
          s * (pos.gear_angle - c.touch_angle) * std::abs(axis.cross(r).dot(c.normal_gear));
      if (c.separation < options.contact_tolerance)
        ++pos.touching;
    }
  return pos;
}

TcaResult
UnloadedTca::run() const
{
  TcaResult result;
  result.mesh_angle = 2 * pi / pinion->teeth();
  const int n       = options.positions_per_mesh * options.mesh_cycles;
  for (int i = 0; i < n; ++i)
    result.positions.push_back(
        at(options.start_angle + result.mesh_angle * i / options.positions_per_mesh));
  summarise(result);
  return result;
}

void
set_contact_geometry(PairContact &c, const Assembly &assembly, const Flank &pinion_flank,
                     const Flank &gear_flank, double phi, double psi)
{
  const FlankPoint p = pinion_flank.evaluate(c.u1, c.v1);
  const FlankPoint g = gear_flank.evaluate(c.u2, c.v2);
  c.position         = assembly.pinion_to_global(p.position, phi);
  c.normal_pinion    = assembly.pinion_vector_to_global(p.normal, phi);
  c.normal_gear      = assembly.gear_vector_to_global(g.normal, psi);
  c.lambda_pinion =
      (c.position - assembly.pinion_to_global(Vec3::Zero(), phi)).cross(c.normal_pinion);
  c.lambda_gear = (c.position - assembly.gear_to_global(Vec3::Zero(), psi)).cross(c.normal_gear);
}

namespace
{
/// Shape operator S (3 x 3, on the tangent plane) of a flank at (u, v) in global coordinates:
/// the normal curvature along a unit tangent t is t . S t (negative where the surface bends away
/// from its outward normal).
Eigen::Matrix3d
shape_operator(const Flank &f, double u, double v, const std::function<Vec3(const Vec3 &)> &turn)
{
  const FlankPoint p    = f.evaluate(u, v);
  const auto [n_u, n_v] = f.normal_derivatives(u, v);
  Eigen::Matrix<double, 3, 2> W, N;
  W.col(0) = turn(p.d_du), W.col(1) = turn(p.d_dv);
  N.col(0) = turn(n_u), N.col(1) = turn(n_v);
  return -N * (W.transpose() * W).inverse() * W.transpose();
}
} // namespace

void
set_relative_curvature(PairContact &c, const Assembly &assembly, const Flank &pinion_flank,
                       const Flank &gear_flank, double phi, double psi)
{
  const Eigen::Matrix3d Sp = shape_operator(pinion_flank, c.u1, c.v1, [&](const Vec3 &x) {
    return assembly.pinion_vector_to_global(x, phi);
  });
  const Eigen::Matrix3d Sg = shape_operator(gear_flank, c.u2, c.v2, [&](const Vec3 &x) {
    return assembly.gear_vector_to_global(x, psi);
  });
  // Gap along n_p between the surfaces: -(L_p + L_g)/2, L the normal-curvature forms.
  const Vec3                  n  = c.normal_pinion;
  const Vec3                  e1 = n.unitOrthogonal(), e2 = n.cross(e1);
  Eigen::Matrix<double, 3, 2> E;
  E.col(0) = e1, E.col(1) = e2;
  Eigen::Matrix2d B = -E.transpose() * (Sp + Sg) * E;
  B                 = 0.5 * (B + B.transpose());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(B);
  c.curvature_min   = eig.eigenvalues()[0];
  c.curvature_max   = eig.eigenvalues()[1];
  c.major_direction = E * eig.eigenvectors().col(0);
  // The eigenvector's sign is arbitrary (rounding turns it over): the one along the pinion's
  // face (its profile where the direction crosses the face at right angles).
  const FlankPoint f   = pinion_flank.evaluate(c.u1, c.v1);
  const Vec3       dv  = assembly.pinion_vector_to_global(f.d_dv, phi).normalized();
  const Vec3       du  = assembly.pinion_vector_to_global(f.d_du, phi).normalized();
  const double     key = std::abs(c.major_direction.dot(dv)) > 1e-6 ? c.major_direction.dot(dv)
                                                                    : c.major_direction.dot(du);
  if (key < 0)
    c.major_direction = -c.major_direction;
}

std::pair<double, double>
contact_ellipse(const PairContact &c, double approach)
{
  auto axis = [&](double k) { return k > 2 * approach ? std::sqrt(2 * approach / k) : 1.0; };
  return {axis(c.curvature_min), axis(c.curvature_max)};
}

void
summarise(TcaResult &result)
{
  int touching = 0;
  result.transfers.clear();
  for (std::size_t i = 0; i < result.positions.size(); ++i)
    {
      const TcaPosition &p = result.positions[i];
      touching += p.touching;
      if (i > 0)
        {
          const TcaPosition &q = result.positions[i - 1];
          if (p.pairs[p.leading].pinion_tooth != q.pairs[q.leading].pinion_tooth)
            result.transfers.push_back(int(i));
        }
    }
  result.mean_pairs_in_contact =
      result.positions.empty() ? 0 : double(touching) / result.positions.size();
}
} // namespace gearkit
