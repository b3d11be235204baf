#!/usr/bin/env python3
"""The layers of the code (README, Layout): every #include "signorini/<folder>/..." in src/ and include/ names a folder
of the same layer or of one below it, so no include runs back up (app -> post -> loop -> contact -> linalg -> fem, io
-> mesh, bc, obstacles -> options -> core); and tests/unit/ and include/signorini/ have a folder for each of src/'s."""
import os
import re
import sys

SOURCE = sys.argv[1]
# Layer of each folder: a folder may include its own layer and the ones below.
LAYERS = {"core": 0, "options": 1, "mesh": 2, "bc": 2, "obstacles": 2, "fem": 3, "io": 3, "linalg": 4, "contact": 5,
          "loop": 6, "post": 7, "app": 8}
INCLUDE = re.compile(r'^\s*#\s*include\s+"signorini/([a-z_]+)/', re.M)

failures = []
folders = set()
for top in ("src", "include/signorini"):
    root = os.path.join(SOURCE, top)
    for folder in sorted(os.listdir(root)):
        path = os.path.join(root, folder)
        if not os.path.isdir(path):
            continue
        folders.add(folder)
        if folder not in LAYERS:
            failures.append(f"{top}/{folder}: a folder that no layer names (add it to the README's layers and here)")
            continue
        for name in sorted(os.listdir(path)):
            with open(os.path.join(path, name)) as f:
                for included in INCLUDE.findall(f.read()):
                    if LAYERS.get(included, 99) > LAYERS[folder]:
                        failures.append(f"{top}/{folder}/{name} includes signorini/{included}/ (a layer above)")
for folder in sorted(folders):
    for mirror in ("src", "include/signorini"):
        if not os.path.isdir(os.path.join(SOURCE, mirror, folder)):
            failures.append(f"{mirror}/{folder} is missing: include/signorini/ mirrors src/")
unit = os.path.join(SOURCE, "tests", "unit")
for folder in sorted(os.listdir(unit)):
    if os.path.isdir(os.path.join(unit, folder)) and folder not in folders:
        failures.append(f"tests/unit/{folder} mirrors no folder of src/")
for failure in failures:
    print("FAIL " + failure)
print(f"{len(folders)} folders checked, {len(failures)} failure(s)")
sys.exit(1 if failures else 0)
