#!/usr/bin/env python3
"""tools/check_docs.py on fixture trees: the clean one passes, each broken one
fails with the problem named at its file and line.

usage: test_check_docs.py CHECK_DOCS_PY FIXTURES_DIR
"""
import os
import subprocess
import sys

EXPECTED = {  # fixture -> (exit code, lines the output must contain)
    "clean": (0, ["check_docs: 2 files, 0 problems"]),
    "broken_file": (1, ["README.md:3: link 'docs/method.md' names docs/method.md, which does not exist"]),
    "broken_anchor": (1, ["README.md:3: link 'docs/guide.md#3-step-three': docs/guide.md has no heading "
                          "with anchor '#3-step-three'"]),
    "machine_path": (1, ["README.md:3: '/tmp/build/bin/rollsense' is a path on one particular machine",
                         "README.md:3: '/work/shared/reference/simulation.md' is a path on one particular machine",
                         "check_docs: 2 files, 2 problems"]),
}


def main():
    script, fixtures = sys.argv[1], sys.argv[2]
    failures = []
    for name, (code, needles) in EXPECTED.items():
        run = subprocess.run([sys.executable, script, os.path.join(fixtures, name)],
                             capture_output=True, text=True)
        if run.returncode != code:
            failures.append(f"{name}: exit {run.returncode}, expected {code}\n{run.stdout}{run.stderr}")
        for needle in needles:
            if needle not in run.stdout:
                failures.append(f"{name}: output lacks '{needle}'\n{run.stdout}{run.stderr}")
    for f in failures:
        print(f)
    print(f"test_check_docs: {len(EXPECTED)} fixtures, {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
