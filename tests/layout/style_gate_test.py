#!/usr/bin/env python3
"""The style gate's own test (ctest style.TidyGateFindsPlantedBugs): tools/check_style.py tidy,
run on a small repository made here with the project's .clang-tidy, must report a bug planted in
a source of a unity batch and one in a source compiled on its own, name the file and line, and
pass the same tree once the bugs are gone. A gate that quietly checked nothing (as when a unity
file, which lives in the build folder, was checked without the project's .clang-tidy: clang-tidy's
default checks ran instead) would pass any tree; this test fails then.

    python3 tests/layout/style_gate_test.py REPO
"""
from __future__ import annotations

import json
import pathlib
import shutil
import subprocess
import sys
import tempfile

# bugprone-use-after-move is one of the project's checks and not among clang-tidy's defaults.
MOVED = """#include <string>
#include <utility>
namespace demo {
std::string %s(std::string s) {
  std::string t = std::move(s);
  return s + t;  // used after the move
}
}  // namespace demo
"""
CLEAN = """#include <string>
namespace demo {
std::string %s(const std::string& s) { return s + s; }
}  // namespace demo
"""


def make_tree(root: pathlib.Path, repo: pathlib.Path, bugs: bool) -> tuple[pathlib.Path, pathlib.Path]:
    src, build = root / "src", root / "build"
    (src / "core").mkdir(parents=True)
    (build / "CMakeFiles" / "demo.dir" / "Unity").mkdir(parents=True)
    shutil.copy(repo / ".clang-tidy", src / ".clang-tidy")
    for name in ("first", "second", "alone"):
        (src / "core" / f"{name}.cpp").write_text((MOVED if bugs and name != "first" else CLEAN) % name)
    unity = build / "CMakeFiles" / "demo.dir" / "Unity" / "unity_0_cxx.cxx"
    unity.write_text("".join(f'#include "{src}/core/{n}.cpp"\n' for n in ("first", "second")))
    (build / "CMakeCache.txt").write_text("")
    flags = ["/usr/bin/c++", f"-I{src}", "-std=c++20", "-Wshadow"]
    commands = [
        {"directory": str(build), "file": str(unity),
         "arguments": flags + ["-o", "CMakeFiles/demo.dir/Unity/unity_0_cxx.cxx.o", "-c", str(unity)]},
        {"directory": str(build), "file": str(src / "core" / "alone.cpp"),
         "arguments": flags + ["-o", "CMakeFiles/demo.dir/core/alone.cpp.o", "-c", str(src / "core" / "alone.cpp")]},
    ]
    (build / "compile_commands.json").write_text(json.dumps(commands))
    return src, build


def run_gate(repo: pathlib.Path, src: pathlib.Path, build: pathlib.Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(repo / "tools" / "check_style.py"), "tidy", "--repo", str(src),
                           "--build", str(build), "--jobs", "2"], capture_output=True, text=True)


def main() -> int:
    repo = pathlib.Path(sys.argv[1]).resolve()
    failures = []
    with tempfile.TemporaryDirectory(prefix="palprig-style-gate-") as tmp:
        src, build = make_tree(pathlib.Path(tmp) / "bugs", repo, bugs=True)
        r = run_gate(repo, src, build)
        out = r.stdout + r.stderr
        if r.returncode != 1:
            failures.append(f"planted bugs: exit {r.returncode}, expected 1")
        for where in ("core/second.cpp:6:", "core/alone.cpp:6:"):
            if where not in out or "bugprone-use-after-move" not in out:
                failures.append(f"planted bugs: no bugprone-use-after-move finding at {where}")
        if "2 translation units of 3 sources" not in out:
            failures.append("the unity batch was not checked as one unit beside the lone source")
        if failures:
            failures.append("its output:\n" + out)

        src, build = make_tree(pathlib.Path(tmp) / "clean", repo, bugs=False)
        r = run_gate(repo, src, build)
        if r.returncode != 0:
            failures.append(f"the clean tree: exit {r.returncode}, expected 0:\n{r.stdout}{r.stderr}")
    for f in failures:
        print("style gate: " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
