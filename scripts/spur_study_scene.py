"""The spur pair of issue 36's studies as a gearkit scene: z 20/31, m 3 mm, b 15 mm, bores 30 and
45 mm, every length times `scale`; the stiffness stage only (finite elements without the error
estimate, loaded contact at `torques` [N m] and `positions` per mesh cycle). `finite_elements`
adds lines to the pair's `Finite elements` section (each "    set name = value\n").
Used by scripts/design_space_study.py and scripts/element_study.py."""


def spur_study_scene(scale=1.0, torques=(100,), positions=20, finite_elements=""):
    s = scale

    def member(name, teeth, bore):
        return f"""    subsection {name}
      set number of teeth = {teeth}
      set normal module   = {3 * s:.9g}
      set face width      = {15 * s:.9g}
      set bore diameter   = {bore * s:.9g}
    end
"""

    return f"""subsection Scene
  set outputs = stiffness
  set pairs   = p
end
subsection Flanks
  subsection p
{member("Pinion", 20, 30)}{member("Gear", 31, 45)}  end
end
subsection Finite elements
  subsection p
    set error estimate = false
{finite_elements}  end
end
subsection Loaded contact
  subsection p
    set torques = {", ".join(f"{t:.9g}" for t in torques)}
    set positions per mesh cycle = {positions}
  end
end
"""
