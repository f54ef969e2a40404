#!/usr/bin/env bash
# Set up everything the tests need, then run the whole suite (arguments go to pytest).
# The default run skips the `slow` tests; `tests/run.sh -m slow` recomputes the stored references in
# tests/references/ and checks them (DYNLAB_REGENERATE_REFERENCES=1 rewrites them instead).
#   - uv (from PyPI) for the project environment
#   - Debian's Chromium, as its headless shell, for the real-browser tests (Playwright drives it; it never downloads one)
#   - Debian's PostgreSQL for the database tests on PostgreSQL (each starts a throwaway cluster on loopback)
#   - Debian's HAProxy for the test of one class on two servers behind a balancer (deploy/haproxy.cfg)
set -euo pipefail
cd "$(dirname "$0")/.."
python3 -m uv --version >/dev/null 2>&1 || python3 -m pip install --quiet uv
MISSING=""
[ -x /usr/bin/chromium-headless-shell ] || MISSING="$MISSING chromium-headless-shell"
ls /usr/lib/postgresql/*/bin/initdb >/dev/null 2>&1 || MISSING="$MISSING postgresql"
[ -x /usr/sbin/haproxy ] || MISSING="$MISSING haproxy"
if [ -n "$MISSING" ]; then
  echo "Installing Debian's$MISSING for the tests..."
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq $MISSING >/dev/null
fi
# Keep compiled bytecode (and pytest's rewritten test modules) in __pycache__ even where the environment says not to
# write it: a run starts dozens of Python processes (served apps, their scene workers, bounded children), and each
# would otherwise compile app/ again from source.
unset PYTHONDONTWRITEBYTECODE
# Fill the numba and derivation caches once, in one process, before the dozens of processes that read them start: on a
# fresh clone each of them would otherwise compile and derive the same kernels and equations at the same time.
python3 -m uv run --group test --group bench --group postgres dynlab warm
# Three xdist workers on an idle machine, two on a busy one (tests/workers.py says why); a -n given here wins.
WORKERS=$(python3 tests/workers.py)
echo "pytest on $WORKERS workers (tests/workers.py)"
exec python3 -m uv run --group test --group bench --group postgres pytest -n "$WORKERS" "$@"
