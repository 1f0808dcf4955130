#include "tca/tooth_pairs.h"

#include "tca/unloaded_tca.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>

namespace gearkit
{
namespace
{
/// Per tooth the member's classes, renumbered densely in their order; returns their count.
int
dense_classes(const MemberFlanks &member, std::vector<int> &classes)
{
  classes.resize(member.teeth());
  for (int k = 0; k < member.teeth(); ++k)
    classes[k] = member.flank_class(k);
  std::vector<int> values = classes;
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  for (int &c : classes)
    c = int(std::lower_bound(values.begin(), values.end(), c) - values.begin());
  return int(values.size());
}

/// Whether the flank has material on both sides of (u, v) along u (or v): false at an edge of
/// its domain or of a chipped region.
bool
smooth(const Flank &f, double u, double v, bool along_u)
{
  const FlankDomain d = f.domain();
  const double      h = 1e-6 * (along_u ? d.u_max - d.u_min : d.v_max - d.v_min);
  for (double sign : {-1.0, 1.0})
    {
      const double uu = along_u ? u + sign * h : u, vv = along_u ? v : v + sign * h;
      if (uu < d.u_min || uu > d.u_max || vv < d.v_min || vv > d.v_max || !f.contains(uu, vv))
        return false;
    }
  return true;
}

struct Sample
{
  double      offset = 0, arm = 0;
  PairContact contact; ///< where it was found (the next sample's search starts around it)
  /// Which flank touches with an edge of its profile (a tip, a chipped region): 0 neither
  /// (flank to flank), 1 the gear's, 2 the pinion's, 3 both. (Along the face a line contact's
  /// closest point may lie on a face end anywhere on the curve: not a kink.)
  int edges = 0;
};

/// One class pair's curve on one side from its representative pairing k.
class CurveWalk
{
public:
  CurveWalk(const UnloadedTca &tca, int k, const ToothPairOptions &o)
      : tca(tca)
      , k(k)
      , options(o)
      , z1(tca.pinion_flanks().teeth())
      , z2(tca.gear_flanks().teeth())
      , ratio(double(z1) / z2)
      , step(2 * pi / z1 / o.samples_per_mesh)
      , s(tca.options_data().side == FlankSide::drive ? 1.0 : -1.0)
  {
  }

  /// Pairing k at local pinion angle i step, if its flanks can meet there; `near` the
  /// neighbouring sample's.
  std::optional<Sample>
  at(int i, const Sample *near = nullptr) const
  {
    return at_angle(i * step, near);
  }

  /// The same at any local pinion angle.
  std::optional<Sample>
  at_angle(double local, const Sample *near = nullptr) const;

  /// The kink between samples a and b (local angles x_a < x_b) whose edges differ: the
  /// change located by bisection to 1e-12 of a mesh cycle, the curve's values on either side
  /// of it. None where a sample between them cannot be found (the pair parts there).
  std::optional<CurveKnot>
  knot(double x_a, const Sample &a, double x_b, const Sample &b) const;

  /// The curve, or nothing when the pair never touches within three mesh cycles of its
  /// centre (why: in `why`).
  std::optional<ToothPairCurve>
  run(std::string &why) const;

private:
  const UnloadedTca      &tca;
  int                     k;
  const ToothPairOptions &options;
  int                     z1, z2;
  double                  ratio, step, s;
};

std::optional<Sample>
CurveWalk::at_angle(double local, const Sample *near) const
{
  const PairContact c = tca.pair(k, local + 2 * pi * k / z1, near ? &near->contact : nullptr);
  if (!c.found)
    return std::nullopt;
  // The contact normal is that of the flank which is smooth at the contact: the gear's, but
  // the pinion's where an edge of the gear flank (its tip, a chip) touches the pinion inside
  // its flank. (Both agree in a tangential contact; at an edge they part by up to tens of
  // degrees before the pair has receded by `recess`.)
  const FlankSide side   = tca.options_data().side;
  const Flank    &pf     = tca.pinion_flanks().flank(c.pinion_tooth, side);
  const Flank    &gf     = tca.gear_flanks().flank(c.gear_tooth, side);
  const bool      gear_u = smooth(gf, c.u2, c.v2, true), gear_v = smooth(gf, c.u2, c.v2, false);
  const bool      pinion_u = smooth(pf, c.u1, c.v1, true), pinion_v = smooth(pf, c.u1, c.v1, false);
  const bool use_pinion = !(gear_u && gear_v) && ((pinion_u && pinion_v) || (!gear_u && pinion_u));
  const Vec3 n          = use_pinion ? c.normal_pinion : c.normal_gear;
  const Assembly &assembly = tca.assembly_data();
  const Vec3      r        = c.position - assembly.gear_centre();
  // offset = psi_touch - 2 pi k / z2 - (z1 / z2) local, formed so that the large angles cancel
  // first.
  return Sample{(c.touch_angle - 2 * pi * k / z2) - ratio * local,
                std::abs(assembly.gear_axis().cross(r).dot(n)), c,
                (gear_u ? 0 : 1) + (pinion_u ? 0 : 2)};
}

std::optional<CurveKnot>
CurveWalk::knot(double x_a, const Sample &a, double x_b, const Sample &b) const
{
  Sample       below = a, above = b;
  const double tolerance = 1e-12 * (2 * pi / z1);
  while (x_b - x_a > tolerance)
    {
      const double                m = (x_a + x_b) / 2;
      const std::optional<Sample> s = at_angle(m, &below);
      if (!s)
        return std::nullopt;
      if (s->edges == a.edges)
        x_a = m, below = *s;
      else
        x_b = m, above = *s;
    }
  CurveKnot k;
  k.at        = (x_a + x_b) / 2;
  k.offset[0] = below.offset, k.offset[1] = above.offset;
  k.arm[0] = below.arm, k.arm[1] = above.arm;
  return k;
}

std::optional<ToothPairCurve>
CurveWalk::run(std::string &why) const
{
  // The pairing's centre: local angle 0, else the nearest position where it touches (within
  // three mesh cycles).
  const int             n      = options.samples_per_mesh;
  const int             coarse = std::max(1, n / 8);
  int                   centre = 0;
  std::optional<Sample> first  = at(0);
  for (int j = 1; !first && j * coarse <= 3 * n; ++j)
    for (int sign : {-1, 1})
      if (!first)
        {
          centre = sign * j * coarse;
          first  = at(centre);
        }
  if (!first)
    {
      std::ostringstream m;
      m << "tooth pair curves: pinion tooth " << mod(-k, z1) << " and gear tooth "
        << mod(s > 0 ? k - 1 : k, z2) << " never meet on the " << to_string(tca.options_data().side)
        << " flanks within three mesh cycles of their pairing's centre; expected flanks that "
           "mesh (check the centre distance, hands and face widths)";
      why = m.str();
      return std::nullopt;
    }

  // Outwards both ways while the pair touches, through the first sample whose touch angle has
  // fallen more than `recess` (along the normal) behind the most advanced one so far.
  std::vector<Sample> below, above;
  double              lead  = s * first->offset; // the most advanced touch so far
  const int           limit = z1 * n / 2;        // half a turn: never reached by a real mesh
  for (int direction : {1, -1})
    {
      std::vector<Sample> &side = direction > 0 ? above : below;
      for (int i = centre + direction;; i += direction)
        {
          if (std::abs(i - centre) > limit)
            throw InputError("tooth pair curves: a pairing touches over half a turn of the "
                             "pinion; expected flanks of a gear mesh");
          const std::optional<Sample> t = at(i, side.empty() ? &*first : &side.back());
          if (!t)
            break;
          side.push_back(*t);
          lead = std::max(lead, s * t->offset);
          if (t->arm * (lead - s * t->offset) > options.recess)
            break;
        }
    }

  ToothPairCurve curve;
  curve.step  = step;
  curve.start = (centre - int(below.size())) * step;
  std::vector<Sample> samples(below.rbegin(), below.rend());
  samples.push_back(*first);
  samples.insert(samples.end(), above.begin(), above.end());
  for (std::size_t i = 0; i < samples.size(); ++i)
    {
      curve.offset.push_back(samples[i].offset), curve.arm.push_back(samples[i].arm);
      if (i > 0 && samples[i].edges != samples[i - 1].edges)
        if (const std::optional<CurveKnot> k =
                knot(curve.start + double(i - 1) * step, samples[i - 1],
                     curve.start + double(i) * step, samples[i]))
          curve.knots.push_back(*k);
    }
  return curve;
}
} // namespace

ToothPairTables
tooth_pair_tables(std::shared_ptr<const MemberFlanks> pinion,
                  std::shared_ptr<const MemberFlanks> gear, double centre_distance,
                  const Misalignment &misalignment, const ToothPairOptions &options)
{
  if (!pinion || !gear)
    throw InputError("tooth pair curves: both members' flanks are needed");
  if (options.samples_per_mesh < 1 || !(options.recess > 0) || !std::isfinite(options.recess))
    throw InputError("tooth pair curves: samples per mesh (>= 1) and the recess (> 0, finite) "
                     "must be positive");
  ToothPairTables tables;
  const int       z1 = pinion->teeth(), z2 = gear->teeth();
  tables.pinion_teeth   = z1;
  tables.gear_teeth     = z2;
  tables.pinion_classes = dense_classes(*pinion, tables.pinion_class);
  tables.gear_classes   = dense_classes(*gear, tables.gear_class);

  for (FlankSide side : {FlankSide::drive, FlankSide::coast})
    {
      TcaOptions o;
      o.side            = side;
      o.profile_samples = options.profile_samples;
      o.face_samples    = options.face_samples;
      o.robust_search   = true;
      const UnloadedTca tca(pinion, gear, centre_distance, misalignment, o);

      // A representative pairing of every class pair that meets, the smallest |k|: pairing k
      // has pinion tooth mod(-k, z1) and gear tooth mod(k - 1, z2) (drive) or mod(k, z2).
      const int        classes = tables.pinion_classes * tables.gear_classes;
      std::vector<int> pairing(classes, 0);
      std::vector<int> seen(classes, 0);
      const int        period = z1 / std::gcd(z1, z2) * z2; // pairings repeat after lcm(z1, z2)
      int              left   = classes;
      for (int j = 0; j < period && left > 0; ++j)
        {
          const int k = j % 2 ? (j + 1) / 2 : -j / 2; // 0, 1, -1, 2, -2, ...
          const int c = tables.pinion_class[mod(-k, z1)] * tables.gear_classes +
                        tables.gear_class[mod(side == FlankSide::drive ? k - 1 : k, z2)];
          if (!seen[c])
            seen[c] = 1, pairing[c] = k, --left;
        }
      auto       &curves = tables.curves[int(side == FlankSide::drive ? drive_side : coast_side)];
      std::string never;
      int         touching = 0;
      curves.resize(classes);
      for (ToothPairCurve &curve : curves)
        curve.step = 2 * pi / z1 / options.samples_per_mesh;
      for (int c = 0; c < classes; ++c)
        if (seen[c]) // else its teeth never mate (tooth counts with a common factor): no samples
          {
            const int k = pairing[c];
            for (const auto &[member, tooth, name] :
                 {std::tuple{pinion.get(), mod(-k, z1), "pinion"},
                  std::tuple{gear.get(), mod(side == FlankSide::drive ? k - 1 : k, z2), "gear"}})
              if (!member->has(tooth, side))
                throw InputError("tooth pair curves: the " + std::string(name) + " has no " +
                                 to_string(side) + " flank on tooth " + std::to_string(tooth) +
                                 "; the curves need both flanks of every tooth");
            // a class pair that never touches while others do: a tooth that is gone (a chip
            // down to the root), its curve left empty (never touching)
            if (auto curve = CurveWalk(tca, k, options).run(never))
              curves[c] = std::move(*curve), ++touching;
          }
      if (touching == 0)
        throw InputError(never);
    }
  return tables;
}
} // namespace gearkit
