#include "geometry/member_flanks.h"

#include "geometry/point_cloud.h"

#include <Eigen/Geometry>

#include <algorithm>

namespace gearkit
{
namespace
{
constexpr int guess_grid = 9; // coarse samples per parameter direction
}

/// A flank with its coarse (r, z) sample and KD-tree.
struct MemberFlanks::Entry
{
  std::unique_ptr<Flank> flank;
  PointCloud<2>          rz;     ///< (r, z) of the samples
  std::vector<double>    params; ///< u0, v0, u1, v1, ...
};

MemberFlanks::MemberFlanks()  = default;
MemberFlanks::~MemberFlanks() = default;

void
MemberFlanks::add(int tooth, FlankSide side, std::unique_ptr<Flank> flank)
{
  auto              e = std::make_unique<Entry>();
  const FlankDomain d = flank->domain();
  for (int i = 0; i < guess_grid; ++i)
    for (int j = 0; j < guess_grid; ++j)
      {
        const double u = d.u_min + (d.u_max - d.u_min) * i / (guess_grid - 1);
        const double v = d.v_min + (d.v_max - d.v_min) * j / (guess_grid - 1);
        const Vec3   p = flank->evaluate(u, v).position;
        e->rz.points.emplace_back(p.head<2>().norm(), p.z());
        e->params.insert(e->params.end(), {u, v});
      }
  e->flank = std::move(flank);
  e->rz.build();
  flanks[{tooth, int(side)}] = std::move(e);
}

bool
MemberFlanks::has(int tooth, FlankSide side) const
{
  return flanks.count({tooth, int(side)}) > 0;
}

const Flank &
MemberFlanks::flank(int tooth, FlankSide side) const
{
  const auto it = flanks.find({tooth, int(side)});
  if (it == flanks.end())
    throw InputError("no " + std::string(to_string(side)) + " flank of tooth " +
                     std::to_string(tooth) + " (it was not measured)");
  return *it->second->flank;
}

Vec3
MemberFlanks::face_direction(const Vec3 &) const
{
  return Vec3::UnitZ();
}

std::pair<double, double>
MemberFlanks::rotational_parameters(const Vec3 &) const
{
  throw InputError("member flanks: these flanks have no parametrisation by the rotational "
                   "projection (measured flanks: use the theoretical member's)");
}

int
MemberFlanks::flank_class(int tooth) const
{
  return tooth;
}

bool
MemberFlanks::teeth_alike() const
{
  for (int k = 0; k < teeth(); ++k)
    if (flank_class(k) != 0)
      return false;
  return true;
}

int
InvoluteMemberFlanks::flank_class(int tooth) const
{
  if (tooth < 0 || tooth >= teeth())
    throw InputError(gear->data().name + ": tooth index " + std::to_string(tooth) +
                     " is outside [0, " + std::to_string(teeth() - 1) + "]");
  return classes[tooth];
}

std::pair<double, double>
InvoluteMemberFlanks::rotational_parameters(const Vec3 &x) const
{
  return {gear->roll_angle(std::max(std::hypot(x.x(), x.y()), gear->base_radius)), x.z()};
}

std::pair<double, double>
MemberFlanks::guess(int tooth, FlankSide side, double radius, double z) const
{
  const Entry &e     = *flanks.at({tooth, int(side)});
  const auto   index = e.rz.nearest({radius, z}).first;
  return {e.params[2 * index], e.params[2 * index + 1]};
}

InvoluteMemberFlanks::InvoluteMemberFlanks(std::shared_ptr<const InvoluteGear> g)
    : gear(std::move(g))
{
  for (int k = 0; k < gear->teeth(); ++k)
    for (FlankSide side : {FlankSide::drive, FlankSide::coast})
      add(k, side, std::make_unique<InvoluteFlank>(gear->flank(k, side)));

  // Tooth classes: pitch deviations and runout make every tooth its own.
  const InvoluteGearData &d = gear->data();
  const bool              pitch_errors =
      std::any_of(d.single_pitch_deviations.begin(), d.single_pitch_deviations.end(),
                  [](double f) { return f != 0; });
  std::vector<bool> nominal(gear->teeth(), !pitch_errors && d.runout.eccentricity == 0);
  for (const EccentricTooth &e : d.eccentric_teeth)
    if (e.offset != 0)
      nominal[e.tooth] = false;
  for (const ChippedTooth &c : d.chipped_teeth)
    nominal[c.tooth] = false;
  for (const std::vector<ToothModifications> *own :
       {&d.drive_tooth_deviations, &d.coast_tooth_deviations})
    for (std::size_t k = 0; k < own->size(); ++k)
      if ((*own)[k].any())
        nominal[k] = false;
  const bool any_nominal = std::find(nominal.begin(), nominal.end(), true) != nominal.end();
  int        next        = any_nominal ? 1 : 0;
  for (int k = 0; k < gear->teeth(); ++k)
    classes.push_back(nominal[k] ? 0 : next++);
}

namespace
{
/// A flank turned rigidly about the member axis: a measured flank standing in for a tooth that
/// was not measured.
class RotatedFlank : public Flank
{
public:
  RotatedFlank(std::shared_ptr<const Flank> base, double angle)
      : base(std::move(base))
      , rotation(Eigen::AngleAxisd(angle, Vec3::UnitZ()).toRotationMatrix())
  {
  }
  FlankPoint
  evaluate(double u, double v) const override
  {
    FlankPoint p = base->evaluate(u, v);
    p.position   = rotation * p.position;
    p.normal     = rotation * p.normal;
    p.d_du       = rotation * p.d_du;
    p.d_dv       = rotation * p.d_dv;
    return p;
  }
  FlankDomain
  domain() const override
  {
    return base->domain();
  }

private:
  std::shared_ptr<const Flank> base;
  Eigen::Matrix3d              rotation;
};
} // namespace

MeasuredMember
virtual_cmm(const MemberFlanks &member, const std::string &name, int n_profile, int n_face,
            double margin, const std::vector<int> &teeth, bool both_sides)
{
  if (n_profile < 1 || n_face < 1 || !(margin >= 0 && margin < 0.5))
    throw InputError("virtual CMM of " + name + ": grid " + std::to_string(n_profile) + " x " +
                     std::to_string(n_face) + ", margin " + std::to_string(margin) +
                     "; expected at least 1 x 1 points and a margin in [0, 0.5)");
  return virtual_cmm(
      name, member.teeth(),
      [&](int k, FlankSide side) {
        return sample_flank(member.flank(k, side), n_profile, n_face, margin);
      },
      teeth, both_sides);
}

MeasuredMemberFlanks::MeasuredMemberFlanks(const MeasuredMember &m)
    : z(m.teeth)
{
  check_member(m, "measured flanks of " + (m.member.empty() ? std::string("a member") : m.member));
  // Every tooth gets a flank: its own measurement, else the nearest measured tooth's turned
  // into place (the seed measured one tooth per member).
  std::map<std::pair<int, int>, std::shared_ptr<const Flank>> measured;
  for (const MeasuredFlank &f : m.flanks)
    measured[{f.tooth, int(f.side)}] = std::make_shared<InterpolatedFlank>(f);
  std::vector<std::pair<int, int>> sources(z, {-1, -1}); // measured tooth behind each side
  for (FlankSide side : {FlankSide::drive, FlankSide::coast})
    for (int k = 0; k < z; ++k)
      {
        int best = -1, best_distance = z + 1;
        for (const auto &[key, flank] : measured)
          if (key.second == int(side))
            {
              const int d = std::min((k - key.first + z) % z, (key.first - k + z) % z);
              if (d < best_distance)
                best = key.first, best_distance = d;
            }
        if (best >= 0)
          add(k, side,
              std::make_unique<RotatedFlank>(measured.at({best, int(side)}),
                                             2 * pi * (k - best) / z));
        (side == FlankSide::drive ? sources[k].first : sources[k].second) = best;
      }
  // Teeth whose both sides are the same measured flanks turned into place form one class.
  std::map<std::pair<int, int>, int> class_of;
  for (int k = 0; k < z; ++k)
    {
      const auto it = class_of.emplace(sources[k], int(class_of.size())).first;
      classes.push_back(it->second);
    }
}

int
MeasuredMemberFlanks::flank_class(int tooth) const
{
  if (tooth < 0 || tooth >= z)
    throw InputError("measured member: tooth index " + std::to_string(tooth) + " is outside [0, " +
                     std::to_string(z - 1) + "]");
  return classes[tooth];
}
} // namespace gearkit
