#!/usr/bin/env python3
"""The layout rule of docs/developing.md, "Layout", checked on the sources: every #include "folder/..." of a
code folder names a folder it may depend on (arrows point down), and no header is included from
a folder that is not a code folder; and each code folder's README.md names every source file and
script of the folder (by its name without the extension), so a folder's README cannot fall
behind its files. Prints one line per offence and exits 1.

Run: python3 tests/layout/check_layout.py [SOURCE_DIR]   (ctest: layout.IncludesPointDown)
"""
import pathlib
import re
import sys

# What each folder may include besides itself (docs/developing.md, "Layout"; keep the two in step).
DATA = {"models", "formats", "statistics", "study"}
RIG_BASE = {"models", "runtime", "formats"}
ALLOWED = {
    "core": set(),  # the error root: every folder may include it
    "models": set(),
    "runtime": set(),
    "formats": {"models"},
    "statistics": {"models"},
    "study": {"models", "formats", "statistics"},
    "store": DATA,
    "charts": DATA | {"store"},
    "rigs": RIG_BASE,
    "inputs": RIG_BASE,
    "mechanics": {"models", "formats"},
    "controller": RIG_BASE | {"rigs", "inputs"},
    "calibration": RIG_BASE | {"rigs", "inputs", "controller", "statistics", "mechanics"},
    "experiments": RIG_BASE | {"rigs", "inputs", "controller", "statistics", "study"},
    "sessions": RIG_BASE | DATA | {"rigs", "inputs", "controller", "calibration", "experiments", "store"},
    "gui": RIG_BASE | DATA | {"rigs", "inputs", "controller", "calibration", "experiments", "store", "sessions", "charts"},
    "cli": None,    # the top: anything but bench
    "bench": None,
}
# Files whose job puts them above their folder's floor, with the reason.
EXCEPTIONS = {
    # Calibration charts draw sweeps and fits: built only in a rig build (charts/CMakeLists.txt).
    "charts/calibration_charts.hpp": {"calibration"},
    "charts/calibration_charts.cpp": {"calibration"},
    # The finite-element figures draw mechanics' runs: built only in a rig build (charts/CMakeLists.txt).
    "charts/fe_charts.hpp": {"mechanics"},
    "charts/fe_charts.cpp": {"mechanics"},
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/[^"]+"', re.M)


def main() -> int:
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()
    bad = []
    checked = 0
    for folder, allowed in ALLOWED.items():
        for path in sorted((root / folder).glob("*.[ch]pp")):
            rel = path.relative_to(root).as_posix()
            checked += 1
            for target in INCLUDE.findall(path.read_text(errors="replace")):
                if target == folder or target == "core":
                    continue
                if target not in ALLOWED:
                    bad.append(f"{rel}: includes {target}/, which is not a code folder")
                elif allowed is None:
                    if target == "bench":
                        bad.append(f"{rel}: includes bench/")
                elif target not in allowed and target not in EXCEPTIONS.get(rel, set()):
                    bad.append(f"{rel}: includes {target}/, but {folder}/ may depend only on "
                               f"{', '.join(sorted(allowed)) or 'nothing of palprig'}")
    for folder in ALLOWED:
        readme = root / folder / "README.md"
        if not readme.is_file():
            bad.append(f"{folder}/: has no README.md saying its role and its files")
            continue
        text = readme.read_text(errors="replace")
        for path in sorted((root / folder).iterdir()):
            if path.suffix in (".cpp", ".hpp", ".sh", ".py") and path.stem not in text:
                bad.append(f"{folder}/README.md: does not name {path.name}")
    for line in bad:
        print(line)
    print(f"layout: {checked} files checked, {len(bad)} offences (includes against the layout, files a README does not name)")
    return 1 if bad or checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
