#!/usr/bin/env bash
# Lint, format and type checks of app/, configured in pyproject.toml ([tool.ruff], [tool.mypy]); any finding fails.
# Run from a clean clone like tests/run.sh: uv (from PyPI) brings the locked ruff and mypy of the test group.
set -euo pipefail
cd "$(dirname "$0")/.."
python3 -m uv --version >/dev/null 2>&1 || python3 -m pip install --quiet uv
in_env() { python3 -m uv run --group test --group bench --group postgres "$@"; }
in_env ruff check app
in_env ruff format --check app
in_env mypy
