"""Command line: ``dynlab serve [--host H] [--port P]`` and ``dynlab bench [--quick] [--case C]``."""

from __future__ import annotations

import argparse
import logging
import sys

from app.settings import Settings


def _serve(args: argparse.Namespace) -> int:
    import uvicorn

    from app.main import create_app

    settings = Settings.from_env(host=args.host, port=args.port)
    app = create_app(settings)
    print(f"Dynamics Lab: serving on http://{settings.host}:{settings.port}  (Ctrl+C to stop)", flush=True)
    uvicorn.run(app, host=settings.host, port=settings.port, log_level=args.log_level, ws_max_size=64 * 1024 * 1024)
    return 0


def _bench(args: argparse.Namespace) -> int:
    from app.bench.work_precision import main as bench_main

    return bench_main(args.bench_args)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="dynlab", description="Dynamics Lab: interactive engineering dynamics.")
    commands = parser.add_subparsers(dest="command", required=True)
    serve = commands.add_parser("serve", help="run the web application")
    serve.add_argument("--host", default=None, help="interface to bind (default 127.0.0.1; 0.0.0.0 for a classroom LAN)")
    serve.add_argument("--port", type=int, default=None, help="port (default 8000)")
    serve.add_argument("--log-level", default="info", choices=["critical", "error", "warning", "info", "debug"])
    serve.set_defaults(run=_serve)
    bench = commands.add_parser(
        "bench", help="measure speed against error (writes docs/bench/work_precision.json and plots)", add_help=False
    )
    bench.add_argument("bench_args", nargs=argparse.REMAINDER, help="options of the benchmark (see dynlab bench --help)")
    bench.set_defaults(run=_bench)
    args = parser.parse_args(argv)
    logging.basicConfig(level=getattr(logging, getattr(args, "log_level", "warning").upper()), format="%(levelname)s %(name)s: %(message)s")
    return args.run(args)


if __name__ == "__main__":
    sys.exit(main())
