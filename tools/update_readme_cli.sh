#!/usr/bin/env bash
# Regenerates the README's CLI reference from `build/gridrt --help`, so the two never
# drift (tests/app/readme_test.cpp fails when they differ).
set -euo pipefail
cd "$(dirname "$0")/.."
help=$(build/gridrt --help)
python3 - "$help" <<'PY'
import re, sys
readme = open("README.md").read()
block = "<!-- cli-begin -->\n```text\n" + sys.argv[1].rstrip("\n") + "\n```\n<!-- cli-end -->"
readme = re.sub(r"<!-- cli-begin -->.*?<!-- cli-end -->", lambda m: block, readme, flags=re.S)
open("README.md", "w").write(readme)
PY
echo "README.md: CLI reference updated"
