// What the study tests share: the FZG C pair (reference-data.md section 5) without
// modifications as involute members in mesh, steel, the C14 torque, and a tooth compliance of
// the order of the finite elements' (both members): the load spreads along the face, pairs do
// not interact.
#pragma once

#include "stiffness/loaded_contact.h"
#include "tca/assembly.h"
#include "tests/fzg_c_pair.h"

#include <cmath>
#include <memory>

namespace gearkit::test_data
{
inline const StructuralCompliance tooth_compliance = [](const ContactCell &a,
                                                        const ContactCell &b) {
  return a.pair == b.pair ? 4e-10 * std::exp(-std::abs(a.position.z() - b.position.z()) / 5e-3)
                          : 0.0;
};

struct FzgStudyPair
{
  std::shared_ptr<const InvoluteMemberFlanks> pinion, gear;
  Assembly                                    assembly{1, 1};
  LoadedContactOptions                        contact;
  double                                      torque = 0; ///< F_bt of FZG C14 [N m]
  FzgStudyPair()
  {
    const auto [pd, gd]     = fzg_c_pair();
    const auto [p, g]       = create_pair(pd, gd);
    pinion                  = std::make_shared<const InvoluteMemberFlanks>(p);
    gear                    = std::make_shared<const InvoluteMemberFlanks>(g);
    assembly                = Assembly(working_centre_distance(*p, *g), g->teeth());
    contact.pinion_material = contact.gear_material = {206e9, 0.3};
    torque = 5912 * p->base_radius; // on the line of action
  }
};
} // namespace gearkit::test_data
