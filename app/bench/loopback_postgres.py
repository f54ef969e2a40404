"""A throwaway PostgreSQL server on loopback, for the tests and ``dynlab scale-out``: Debian's ``postgresql``
binaries (tests/run.sh installs them), a new cluster in a temporary directory on a free loopback port, trust
authentication, fsync off; stopped and removed afterwards."""

from __future__ import annotations

import os
import shutil
import subprocess
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from app.bench.ports import free_loopback_port


def postgres_bin() -> Path | None:
    """The newest installed PostgreSQL's bin directory (None if none is installed)."""
    found = sorted(Path("/usr/lib/postgresql").glob("*/bin/initdb"))
    return found[-1].parent if found else None


def _as_owner(command: list[str]) -> list[str]:
    """PostgreSQL refuses to run as root: as root, commands run as the ``postgres`` user the package made."""
    return ["runuser", "-u", "postgres", "--", *command] if os.geteuid() == 0 else command


@contextmanager
def postgres_server() -> Iterator[str]:
    """A new PostgreSQL cluster with an empty ``dynlab`` database; yields its SQLAlchemy URL."""
    bin_dir = postgres_bin()
    if bin_dir is None:
        raise RuntimeError("PostgreSQL is not installed: apt-get install postgresql (tests/run.sh does)")
    root = Path(tempfile.mkdtemp(prefix="dynlab-pg-"))
    if os.geteuid() == 0:
        shutil.chown(root, "postgres", "postgres")
    data, port = root / "data", free_loopback_port()
    run = lambda *command: subprocess.run(_as_owner(list(command)), check=True, capture_output=True, timeout=60)  # noqa: E731
    try:
        run(str(bin_dir / "initdb"), "-D", str(data), "-A", "trust", "-U", "dynlab", "--no-sync")
        options = f"-p {port} -k {root} -c listen_addresses=127.0.0.1 -c fsync=off"
        run(str(bin_dir / "pg_ctl"), "-D", str(data), "-o", options, "-l", str(root / "log"), "-w", "start")
        run(str(bin_dir / "createdb"), "-h", "127.0.0.1", "-p", str(port), "-U", "dynlab", "dynlab")
        yield f"postgresql+psycopg://dynlab@127.0.0.1:{port}/dynlab"
    finally:
        stop = _as_owner([str(bin_dir / "pg_ctl"), "-D", str(data), "-m", "immediate", "stop"])
        subprocess.run(stop, capture_output=True, timeout=60)
        shutil.rmtree(root, ignore_errors=True)
