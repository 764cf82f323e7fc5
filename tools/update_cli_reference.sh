#!/usr/bin/env bash
# Regenerates docs/cli.md's reference from `build/gridrt --help`, so the two never drift
# (tests/app/readme_test.cpp fails when they differ).
set -euo pipefail
cd "$(dirname "$0")/.."
help=$(build/gridrt --help)
python3 - "$help" <<'PY'
import re, sys
readme = open("docs/cli.md").read()
block = "<!-- cli-begin -->\n```text\n" + sys.argv[1].rstrip("\n") + "\n```\n<!-- cli-end -->"
readme = re.sub(r"<!-- cli-begin -->.*?<!-- cli-end -->", lambda m: block, readme, flags=re.S)
open("docs/cli.md", "w").write(readme)
PY
echo "docs/cli.md: CLI reference updated"
