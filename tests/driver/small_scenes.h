// Small scenes for the driver tests, as parameter text: the Scene section, spur pairs of the
// Flanks section and the small two-stage train. The text is laid out as the tests' hand-written
// scenes were (two spaces a level, the same alignment), so that a test's regex edits of a scene
// ("set normal module   = 2\n    end\n    subsection Gear") still find their lines.
#pragma once

#include <sstream>
#include <string>
#include <vector>

namespace gearkit::test_data
{
/// `subsection Scene` with this name, outputs, pairs and, unless empty, trains.
inline std::string
scene_section(const std::string &name, const std::string &outputs, const std::string &pairs,
              const std::string &trains = "")
{
  return "subsection Scene\n"
         "  set name    = " +
         name + "\n  set outputs = " + outputs + "\n  set pairs   = " + pairs + "\n" +
         (trains.empty() ? "" : "  set trains  = " + trains + "\n") + "end\n";
}

// A spur pair of the Flanks section. Both members have the module and the face width; the
// extra text (whole lines, indented as the caller likes) ends the Pinion or Gear subsection.
struct SpurPair
{
  std::string name = "p1";
  int         z1 = 19, z2 = 37;
  double      module         = 2; ///< normal module [mm]
  double      face_width     = 0; ///< [mm]; 0: not set (the default)
  int         profile_points = 3; ///< grid profile points; 0: not set (the default)
  int         face_points    = 4; ///< grid face points; 0: not set (the default)
  std::string pinion_extra   = "";
  std::string gear_extra     = "";
};

/// `number` as a scene file spells it: 2, 4.5, 0.05 (at most 6 significant digits).
inline std::string
scene_number(double number)
{
  std::ostringstream text;
  text << number;
  return text.str();
}

/// The subsection Pinion or Gear (`member`) of a spur pair with z teeth and these extra lines.
inline std::string
spur_member(const std::string &member, int z, const SpurPair &pair, const std::string &extra)
{
  std::string text = "    subsection " + member +
                     "\n      set number of teeth = " + std::to_string(z) +
                     "\n      set normal module   = " + scene_number(pair.module) + "\n";
  if (pair.face_width != 0)
    text += "      set face width      = " + scene_number(pair.face_width) + "\n";
  return text + extra + "    end\n";
}

/// `subsection Flanks` with one subsection per pair of `pairs`, in their order.
inline std::string
flanks_section(const std::vector<SpurPair> &pairs)
{
  std::string text = "subsection Flanks\n";
  for (const SpurPair &p : pairs)
    {
      text += "  subsection " + p.name + "\n";
      if (p.profile_points != 0)
        text += "    set grid profile points = " + std::to_string(p.profile_points) + "\n";
      if (p.face_points != 0)
        text += "    set grid face points    = " + std::to_string(p.face_points) + "\n";
      text += spur_member("Pinion", p.z1, p, p.pinion_extra) +
              spur_member("Gear", p.z2, p, p.gear_extra) + "  end\n";
    }
  return text + "end\n";
}

/// The small two-stage train scene (19/37, 20/40, m 2), `m2_extra` ending its mesh m2.
inline std::string
two_stage_train_scene(const std::string &m2_extra = "")
{
  // Bodies a, b, c; meshes m1 (pair p1, a to b) and m2 (pair p2, b to c); a held at 100 rad/s,
  // b's inertia its gears', a small resistive torque on c; 5 ms at 20 kHz.
  return scene_section("small", "train", "p1, p2", "t") +
         flanks_section({{"p1", 19, 37, 2, 10, 3, 2}, {"p2", 20, 40, 2, 10, 3, 2}}) +
         R"(subsection Train
  subsection t
    set bodies = a, b, c
    set meshes = m1, m2
    subsection Run
      set duration    = 0.005
      set sample rate = 20000
    end
    subsection Spectrum
      set spectrogram window = 2
    end
    subsection Bodies
      subsection a
        set inertia       = 1e-4
        set initial speed = 100
        set drive         = constant speed
      end
      subsection b
        set inertia = auto
      end
      subsection c
        set inertia = 2e-3
        set torque  = -0.5
      end
    end
    subsection Meshes
      subsection m1
        set pair        = p1
        set pinion body = a
        set gear body   = b
        set backlash    = 0.05
      end
      subsection m2
        set pair        = p2
        set pinion body = b
        set gear body   = c
        set backlash    = 0.05
)" + m2_extra +
         R"(      end
    end
  end
end
)";
}
} // namespace gearkit::test_data
