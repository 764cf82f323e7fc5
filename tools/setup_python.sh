#!/usr/bin/env bash
# Creates .venv with the Python packages the tools need (tools/requirements.txt, PyPI).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -x .venv/bin/python ]; then
  python3 -m venv .venv
fi
.venv/bin/pip install --quiet --disable-pip-version-check -r tools/requirements.txt
echo "setup_python: .venv ready"
