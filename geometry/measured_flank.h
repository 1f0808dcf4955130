// Measured flanks: CMM point sets per tooth and flank, their plain-text file format, flank
// topography deviation grids (the way gear-measuring machines report), a virtual CMM that samples
// theoretical flanks, and a synthesiser of realistic "measured" flanks. Formats:
// docs/cmm-format.md.
#pragma once

#include "involute_gear.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace gearkit
{
/// The points of one measured flank on an n_profile x n_face grid (profile index from root to
/// tip, face index from -z to +z), row-major: index i_profile * n_face + i_face. Metres, member
/// frame (axis z, tooth 0 centred on +x at z = 0).
struct MeasuredFlank
{
  int               tooth     = 0;
  FlankSide         side      = FlankSide::drive;
  int               n_profile = 0, n_face = 0;
  std::vector<Vec3> points;
  std::vector<Vec3> normals; ///< unit outward normals (probe directions), or empty
};

/// All measured flanks of one member.
struct MeasuredMember
{
  std::string                member; ///< e.g. "pinion"
  int                        teeth = 0;
  std::vector<MeasuredFlank> flanks;
};

/// Samples theoretical flanks like a perfect CMM: every listed tooth (empty = all), both sides,
/// n_profile x n_face points (the seed paper used 261 = 9 x 29), `margin` of each parameter range
/// left out at the edges; with normals.
MeasuredMember
virtual_cmm(const InvoluteGear &gear, const std::string &member, int n_profile, int n_face,
            double margin = 0, const std::vector<int> &teeth = {});

struct CmmWriteOptions
{
  bool millimetres = true; ///< units of the file: mm (else m)
  int  decimals    = 9;    ///< digits after the point (9 in mm = 1e-12 m)
  bool normals     = true; ///< write normals when the flanks have them
};

/// Writes a CMM point file atomically (a temporary file renamed into place).
void
write_cmm_file(const std::string &path, const MeasuredMember &member,
               const CmmWriteOptions &options = {});

/// Reads a CMM point file; throws InputError "<file>:<line>: <what>; expected <what>".
MeasuredMember
read_cmm_file(const std::string &path);

/// Topography of one flank: deviations along the nominal outward normal (positive = material
/// added) at profile positions (diameters, root to tip) x face positions (z from the face middle).
struct FlankTopography
{
  int                 tooth = 0;
  FlankSide           side  = FlankSide::drive;
  std::vector<double> diameters;  ///< [m], n_profile
  std::vector<double> face;       ///< z [m], n_face
  std::vector<double> deviations; ///< [m], row-major i_profile * n_face + i_face
};

struct TopographyMember
{
  std::string                  member;
  int                          teeth = 0;
  std::vector<FlankTopography> flanks;
};

void
write_topography_file(const std::string &path, const TopographyMember &member);
TopographyMember
read_topography_file(const std::string &path);

/// Points of a measured flank from its topography: the nominal involute flank (no modifications)
/// at the grid positions plus deviation * normal.
MeasuredMember
topography_to_points(const InvoluteGear &gear, const TopographyMember &topography);

/// What the synthesiser adds to theoretical flanks (all metres). Each is zero to leave it out.
struct SynthesisOptions
{
  std::uint64_t seed = 1;
  /// Smooth low-order form deviation per flank: random profile slope, helix slope and profile
  /// crowning whose sum stays within +-form_error.
  double form_error = 0;
  /// Waviness: sinusoids along the profile and along the face (arc length, given wavelength),
  /// random phases, total amplitude waviness_amplitude.
  double waviness_amplitude  = 0;
  double waviness_wavelength = 1e-3;
  /// Roughness: a random field with standard deviation `roughness`, correlated over about one
  /// grid step (white noise averaged with its four neighbours).
  double roughness = 0;
  /// Measurement noise: independent Gaussian, standard deviation `noise` (CMM accuracy ~1 um).
  double noise = 0;
  /// Single pitch deviations per tooth, Gaussian with this standard deviation, made to add up to
  /// zero over all teeth; each tooth's flanks turn rigidly about z by its cumulative deviation
  /// divided by the flank's mean radius.
  double pitch_error = 0;
};

/// A realistic "measured" member from a theoretical one (which must carry normals); the same
/// seed gives the same flanks on every platform. Normals are kept (the probe directions).
MeasuredMember
synthesise_measured(const MeasuredMember &theoretical, const SynthesisOptions &options);
} // namespace gearkit
