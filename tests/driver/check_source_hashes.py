#!/usr/bin/python3
"""The code hashes in the stages' cache keys (driver/source_hashes.py) change with the code and
only with it: a reworded help text, a comment or a reformatted line leaves every hash - and so
the finite-element compliance's cache - valid; a changed default, pattern, parameter name or
statement changes the file's hash.

  check_source_hashes.py SOURCE_DIR
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

root = sys.argv[1]
script = os.path.join(root, "driver", "source_hashes.py")
sys.path.insert(0, os.path.dirname(script))
import source_hashes  # noqa: E402

with open(os.path.join(root, "driver", "scene_stiffness.cc"), encoding="utf-8") as fh:
    original = fh.read()


def digest(text, name="scene_stiffness.cc"):
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, name)
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(text)
        return source_hashes.file_digest(path)


def edited(old, new):
    assert original.count(old) == 1, old
    return original.replace(old, new)


base = digest(original)
help_text = '"Element size at the flanks and fillets / m_n."'
unchanged = {
    "help text reworded": edited(help_text, '"The element size at the flanks and fillets, "\n'
                                            '                    "in normal modules."'),
    "comment added": original.replace("namespace gearkit\n{", "namespace gearkit\n{\n// a note\n", 1),
    "lines reflowed": original.replace('Patterns::Double(0.02, 2),', 'Patterns::Double( 0.02,\n 2 ),'),
}
changed = {
    "default": edited('"flank element size", "0.25"', '"flank element size", "0.3"'),
    "pattern": edited("Patterns::Double(0.02, 2)", "Patterns::Double(0.01, 2)"),
    "parameter name": edited('"flank element size", "0.25"', '"flank element sizes", "0.25"'),
    "statement": original.replace("namespace gearkit\n{", "namespace gearkit\n{\nint x = 1;", 1),
}
for what, text in unchanged.items():
    assert text != original, what
    assert digest(text) == base, f"{what}: the hash changed"
for what, text in changed.items():
    assert text != original, what
    assert digest(text) != base, f"{what}: the hash did not change"
# help texts count in the stage files (not scene sections): there a string is code
assert digest(unchanged["help text reworded"], "stage_stiffness.cc") != digest(original, "stage_stiffness.cc")
# string literals keep their content: a '//' inside one is no comment
assert source_hashes.tokens('f("a // b");') != source_hashes.tokens('f("a ");')

# The whole header: a tree whose only difference is a help text gives the same header, byte
# for byte (the compliance stage's key, driver/stages.cc, reads its hashes from it).
with tempfile.TemporaryDirectory() as d:
    headers = []
    for k, text in enumerate((original, unchanged["help text reworded"])):
        tree = os.path.join(d, f"tree{k}")
        shutil.copytree(os.path.join(root, "driver"), os.path.join(tree, "driver"))
        with open(os.path.join(tree, "driver", "scene_stiffness.cc"), "w", encoding="utf-8") as fh:
            fh.write(text)
        out = os.path.join(d, f"h{k}.h")
        subprocess.run([sys.executable, script, "--root", tree, "--output", out,
                        "--folders", "driver", "--files", "driver"], check=True)
        with open(out, encoding="utf-8") as fh:
            headers.append(fh.read())
    assert headers[0] == headers[1]
    assert re.search(r'\{"driver/stage_stiffness\.cc", "[0-9a-f]{16}"\}', headers[0])
print("source hashes: help texts, comments and layout leave them; defaults, patterns, names and "
      f"statements change them ({len(unchanged)} + {len(changed)} edits)")
