// What contact analysis needs of a gear member: its tooth count and the flank surfaces of its
// teeth, whether theoretical (involute) or interpolated from measured points, plus a quick first
// guess of the flank parameters at a given radius and axial position (nanoflann over a coarse
// sample of each flank in the rotation-invariant (r, z) coordinates).
#pragma once

#include "geometry/interpolated_flank.h"
#include "geometry/involute_gear.h"

#include <map>
#include <memory>
#include <vector>

namespace gearkit
{
class MemberFlanks
{
public:
  MemberFlanks(); // out of line, where Entry is complete
  virtual ~MemberFlanks();
  virtual int
  teeth() const = 0;
  /// Throws InputError when the member has no such flank (e.g. an unmeasured tooth).
  const Flank &
  flank(int tooth, FlankSide side) const;
  bool
  has(int tooth, FlankSide side) const;
  /// Flank parameters (u, v) of the coarse sample nearest in (radius, axial position).
  std::pair<double, double>
  guess(int tooth, FlankSide side, double radius, double z) const;
  /// The unit direction along the face width at the point x of the member: the axis +z for
  /// cylindrical gears (the default), the pitch cone's element for bevel gears.
  virtual Vec3
  face_direction(const Vec3 &x) const;
  /// The flank parameters (u, v) of a theoretical flank through the point x, from x's
  /// rotational projection alone (the same for every tooth): reuses a theoretical table at a
  /// measured flank's points. Throws InputError for members without such a parametrisation.
  virtual std::pair<double, double>
  rotational_parameters(const Vec3 &x) const;
  /// The class of a tooth (0 <= tooth < teeth()): teeth of one class have the same flanks, both
  /// sides, up to a rotation about the member axis by their nominal angles 2 pi k / z (so a
  /// contact computed for one of them serves all). Classes are numbered densely from 0. The
  /// default: every tooth its own class (the tooth's index).
  virtual int
  flank_class(int tooth) const;
  /// Every tooth of one class (0): a contact, or a mesh cycle, computed once serves all.
  bool
  teeth_alike() const;

protected:
  /// Implementations add their flanks in the constructor.
  void
  add(int tooth, FlankSide side, std::unique_ptr<Flank> flank);

private:
  struct Entry;
  std::map<std::pair<int, int>, std::unique_ptr<Entry>> flanks;
};

/// Every flank of an involute gear (with its modifications and deviations).
class InvoluteMemberFlanks : public MemberFlanks
{
public:
  explicit InvoluteMemberFlanks(std::shared_ptr<const InvoluteGear> gear);
  int
  teeth() const override
  {
    return gear->teeth();
  }
  const InvoluteGear &
  involute() const
  {
    return *gear;
  }
  /// Roll angle at the radius of x (at least the base circle), and z.
  std::pair<double, double>
  rotational_parameters(const Vec3 &x) const override;
  /// Class 0: every nominal tooth (no nonzero single pitch deviation anywhere in the data, as
  /// cumulative pitch deviations move every tooth; no runout; neither an eccentric nor a chipped
  /// tooth); every other tooth a class of its own (1, 2, ... in tooth order; from 0 when no
  /// tooth is nominal).
  int
  flank_class(int tooth) const override;

private:
  std::shared_ptr<const InvoluteGear> gear;
  std::vector<int>                    classes; ///< per tooth
};

/// A perfect CMM of any member's flanks: n_profile x n_face points per flank (sample_flank),
/// `margin` of each parameter range left out at the edges; see virtual_cmm in measured_flank.h.
MeasuredMember
virtual_cmm(const MemberFlanks &member, const std::string &name, int n_profile, int n_face,
            double margin = 0, const std::vector<int> &teeth_to_measure = {},
            bool both_sides = true);

/// The measured flanks of a member, interpolated (InterpolatedFlank).
class MeasuredMemberFlanks : public MemberFlanks
{
public:
  explicit MeasuredMemberFlanks(const MeasuredMember &member);
  int
  teeth() const override
  {
    return z;
  }
  /// Teeth whose flanks (both sides) are the same measured flanks turned into place share a
  /// class; a tooth measured itself has one of its own.
  int
  flank_class(int tooth) const override;

private:
  int              z;
  std::vector<int> classes; ///< per tooth
};
} // namespace gearkit
