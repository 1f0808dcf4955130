// Measured flanks: CMM point sets per tooth and flank, their plain-text file format, flank
// topography deviation grids (the way gear-measuring machines report), a virtual CMM that samples
// theoretical flanks, and a synthesiser of realistic "measured" flanks. File formats:
// docs/cmm-format.md.
//
// Frame of every point and file: the member frame, member axis = z, tooth k nominally at the
// polar angle 2 pi k / z. Cylindrical gears (involute_gear.h): face z = -b/2 .. b/2, tooth 0
// centred on +x in the section z = 0. Spiral bevel gears (BevelMemberFlanks, bevel_gear.h): cone
// apex at the origin, teeth toward +z, tooth 0 centred on +x at the mean point of the pitch cone
// (cone distance A_m). SI units.
#pragma once

#include "geometry/involute_gear.h"

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace gearkit
{
/// The points of one measured flank on an n_profile x n_face grid (profile index from root to
/// tip, face index from -z to +z), row-major: index i_profile * n_face + i_face. Metres.
struct MeasuredFlank
{
  int               tooth     = 0;
  FlankSide         side      = FlankSide::drive;
  int               n_profile = 0, n_face = 0;
  std::vector<Vec3> points;
  std::vector<Vec3> normals; ///< unit outward normals (probe directions), or empty
};

/// The measured flanks of one member: any subset of (tooth, side), each at most once.
struct MeasuredMember
{
  std::string                member; ///< e.g. "pinion"
  int                        teeth = 0;
  std::vector<MeasuredFlank> flanks;
};

/// The checks every consumer of a MeasuredMember needs (teeth, distinct flanks in range, points
/// on their grid, finite, unit normals where given; `need_normals`: every point has one);
/// throws InputError prefixed by `context`.
void
check_member(const MeasuredMember &member, const std::string &context, bool need_normals = false);

/// A perfect CMM: `sample(tooth, side)` gives each flank's grid (FlankGrid u = profile, v = face)
/// with normals. Measures the listed teeth (empty = all, in the order given), the drive flank and
/// with `both_sides` also the coast flank. Throws InputError for a tooth outside [0, teeth).
MeasuredMember
virtual_cmm(const std::string &member, int teeth,
            const std::function<FlankGrid(int tooth, FlankSide side)> &sample,
            const std::vector<int> &teeth_to_measure = {}, bool both_sides = true);

/// The same for the flanks of an involute gear, sampled with sample_flank on n_profile x n_face
/// points (default 29 x 9 = 261, the seed paper's count laid out as cylindrical gears are
/// measured: dense along the profile, where the transmission error lives, 9 lead lines),
/// `margin` of each parameter range left out at every edge.
MeasuredMember
virtual_cmm(const InvoluteGear &gear, const std::string &member, int n_profile = 29, int n_face = 9,
            double margin = 0, const std::vector<int> &teeth_to_measure = {},
            bool both_sides = true);

struct CmmWriteOptions
{
  bool millimetres = true; ///< units of the file: mm, else m
  int  decimals    = 9;    ///< digits after the point in the file's unit (9 in mm = 1e-12 m)
  bool normals     = true; ///< write normals (when every flank has them)
};

/// Writes a CMM point file atomically: to `path + ".tmp"`, then renamed into place. Throws
/// InputError (and leaves no file behind) for an inconsistent member or a failed write.
void
write_cmm_file(const std::string &path, const MeasuredMember &member,
               const CmmWriteOptions &options = {});

/// Reads a CMM point file; flanks in file order, points in grid order whatever the line order.
/// Throws InputError "<file>:<line>: <what is wrong>; expected <what is allowed>".
MeasuredMember
read_cmm_file(const std::string &path);

/// The same from a stream (e.g. a string, as the fuzz target reads); `name` stands for the file
/// in the messages.
MeasuredMember
read_cmm(std::istream &in, const std::string &name);

/// Topography of one flank: deviations along the nominal outward normal (positive = material
/// added) at profile positions given as diameters (root to tip) x face positions (z from the
/// face middle), both strictly increasing.
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

/// Writes a topography file (positions in mm, deviations in um) atomically, as write_cmm_file.
void
write_topography_file(const std::string &path, const TopographyMember &member);

/// Reads a topography file; errors as read_cmm_file.
TopographyMember
read_topography_file(const std::string &path);

/// The same from a stream; `name` stands for the file in the messages.
TopographyMember
read_topography(std::istream &in, const std::string &name);

/// Points of the measured flanks from their topography: the nominal involute flank (no
/// modifications; InvoluteFlank::nominal at roll angle xi(d/2) and z) plus deviation * normal,
/// with those normals. Diameters must lie in [d_Ff, d_a] and face positions in [-b/2, b/2].
MeasuredMember
topography_to_points(const InvoluteGear &gear, const TopographyMember &topography);

/// What the synthesiser adds to theoretical flanks (all metres; zero leaves a part out).
struct SynthesisOptions
{
  std::uint64_t seed = 1;
  /// Smooth low-order form deviation per flank: a random profile slope, helix slope, profile
  /// crowning and lead crowning (each coefficient uniform in [-1, 1]) scaled so that the largest
  /// |deviation| on the flank is form_error.
  double form_error = 0;
  /// Waviness: a sinusoid along the profile plus one along the face (arc length of the grid's
  /// middle column and row, wavelength waviness_wavelength, 0 = none), each of amplitude
  /// waviness_amplitude / 2 with a random phase, so |waviness| <= waviness_amplitude.
  double waviness_amplitude  = 0;
  double waviness_wavelength = 1e-3;
  /// Roughness: Gaussian white noise averaged over each grid point and its four neighbours
  /// (correlated over about one grid step), standard deviation `roughness`.
  double roughness = 0;
  /// Measurement noise: independent Gaussian per point with standard deviation `noise`.
  double noise = 1e-6;
  /// Single pitch deviations f_p (from tooth k-1 to k) for all teeth of the member, Gaussian with
  /// this standard deviation, made to sum to zero; the cumulative deviations F_k, shifted to zero
  /// mean (the member as a whole is not turned), turn each flank rigidly about z by
  /// F_k / (mean radius of its points), normals included.
  double pitch_error = 0;
};

/// A realistic "measured" member from a theoretical one whose flanks carry normals: every
/// deviation but pitch moves the points along those normals; normals are kept (probe directions,
/// turned with the pitch). Deterministic: the same seed gives the same flanks on every platform
/// (std::mt19937_64 with its own uniform and Box-Muller transforms), and every random number is
/// drawn whatever the amplitudes, so switching one part on leaves the others' realisation alone.
MeasuredMember
synthesise_measured(const MeasuredMember &theoretical, const SynthesisOptions &options);
} // namespace gearkit
