// Hexahedral mesh of a multi-tooth segment of a face-milled spiral bevel member, built from its
// generated flanks (geometry/face_milling.h) and written through gmsh's API.
//
// The flanks are parametric surfaces, not CAD, so the mesh is a structured multiblock one in the
// blank's natural coordinates (A, h, theta): cone distance, height above the pitch cone, polar
// angle. A point is (r cos theta, r sin theta, axial) with (axial, r) = blank.axial_plane(A, h),
// and the volume element is r dA dh dtheta. Every section A = const (a back cone, normal to the
// pitch cone) has the same topology: per tooth a block between the coast side (upper half of the
// root fillet, then the working flank) and the drive side, across the tooth graded from the
// loaded flank's element size to the other's; below it a rim block over the whole segment from
// the inner cone (h_f + rim thickness below the pitch cone) up to the root lands, the lower
// fillet halves and the teeth. Sections follow the spiral: flank nodes are exact flank points
// at every station A_k (toe to heel), so the loaded flanks need no projection.
//
// Physical groups: as the involute segments (tooth_segment.h, namespace boundary): 1 "bore" (the
// inner cone, held), 2 "cut_start" / 3 "cut_end" (through the middle of the root land before
// the first and after the last tooth, smaller / larger polar angle), 4 "end_front" (toe),
// 5 "end_back" (heel), 6 "free" (tip lands, fillets, root lands), 10 + 2 i / 11 + 2 i the drive
// / coast working flank of segment tooth i; volume 1 "body". A .json sidecar as for the
// involute segments; its analytic volume is integrated independently of the mesh: per section
// by Green's theorem along finely sampled exact boundaries, Gauss-Legendre over A.
#pragma once

#include "geometry/bevel_gear.h"
#include "meshes/tooth_segment.h"

#include <string>

namespace gearkit
{
/// Writes the segment of `member` (needs a blade edge radius > 0: the fillet closes each tooth
/// to the root cone) to `path` (.msh 4.1) and `path`.json via temporary files. Options as for
/// involute segments: teeth, central_tooth, flank_size (default module / 5), other_size,
/// fine_side, far_size (default module), face_layers (default F / (2 flank_size)), and
/// rim_thickness (default 3.5 module); `module` is the mean normal module. Throws InputError for
/// bad options or a folded element (naming the place).
SegmentMeshInfo
write_bevel_segment_mesh(const BevelMemberFlanks &member, double module,
                         const SegmentMeshOptions &options, const std::string &path);

/// The segment's volume from the exact surfaces (see above) [m^3]; `samples` points per fillet
/// half and flank.
double
bevel_segment_volume(const BevelMemberFlanks &member, const SegmentMeshOptions &options,
                     double module, int samples = 96);
} // namespace gearkit
