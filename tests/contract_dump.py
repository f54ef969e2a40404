"""Dump what a running server answers, to compare two versions of the app (a refactor must change nothing).

Usage, against `dynlab serve` started as the README says (any port)::

    python tests/contract_dump.py --url http://127.0.0.1:8000 --out /tmp/before.json
    # ... change the code, restart the server ...
    python tests/contract_dump.py --url http://127.0.0.1:8000 --out /tmp/after.json
    python tests/contract_dump.py --compare /tmp/before.json /tmp/after.json

It records the OpenAPI document, every read-only GET of the API, every page's visible text, each scene's session
and playback answers, and each scene's simulate answer for its defaults and a few integration controls (good and
bad: a 422's ``loc`` and message are contracts too), each worked example's solution, and each system's equations
and right-hand side. Fields that measure this machine (CPU seconds, uptime, load) are masked.
"""

from __future__ import annotations

import argparse
import html
import json
import re
import sys
import time
from html.parser import HTMLParser
from typing import Any

import httpx

#: Keys whose values measure the machine or the moment (or whether a derivation was in the disk cache), not the app.
VOLATILE_KEYS = re.compile(r"cached|derive_s|compile_s|cpu|uptime|wall|elapsed|load|_ms$|^ms_|seconds_running|started|now|pid|rss|memory")

#: Integration controls asked of every scene's simulate beside its defaults (an integrated scene answers, a closed
#: form refuses with a 422 naming the field; both answers are contracts).
SIMULATE_VARIANTS: tuple[dict[str, Any], ...] = (
    {},
    {"t_end": 1.5, "frame_rate": 30},
    {"t_end": 1.0, "method": "rk4", "steps_per_frame": 3},
    {"t_end": 1.0, "method": "dopri5", "rtol": 1e-7},
    {"t_end": 1.0, "method": "no-such-method"},
    {"t_end": 1.0, "algorithm": "baumgarte"},
)

SESSION_ID = "c0ffee00c0ffee00"

#: How often a 429/503 is asked again (a typed derivation keeps answering 429 on a machine busy for minutes).
RETRIES = 4


class _VisibleText(HTMLParser):
    """The text a reader sees: no scripts, styles or tags."""

    def __init__(self) -> None:
        super().__init__()
        self.parts: list[str] = []
        self._hidden = 0

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        if tag in ("script", "style"):
            self._hidden += 1

    def handle_endtag(self, tag: str) -> None:
        if tag in ("script", "style") and self._hidden:
            self._hidden -= 1

    def handle_data(self, data: str) -> None:
        if not self._hidden and data.strip():
            self.parts.append(" ".join(data.split()))


def visible_text(page: str) -> str:
    parser = _VisibleText()
    parser.feed(page)
    return "\n".join(parser.parts)


def masked(value: Any) -> Any:
    if isinstance(value, dict):
        return {k: "<volatile>" if VOLATILE_KEYS.search(k) else masked(v) for k, v in value.items()}
    if isinstance(value, list):
        return [masked(v) for v in value]
    return value


def _answer(response: httpx.Response) -> dict[str, Any]:
    try:
        body: Any = response.json()
    except ValueError:
        body = visible_text(response.text)
    return {"status": response.status_code, "body": masked(body)}


class _PatientClient(httpx.Client):
    """Asks again after a 429/503's Retry-After (a busy machine is not a difference between versions)."""

    def request(self, *args: Any, **kwargs: Any) -> httpx.Response:  # type: ignore[override]
        for _ in range(RETRIES):
            response = super().request(*args, **kwargs)
            if response.status_code not in (429, 503):
                return response
            time.sleep(float(response.headers.get("retry-after", "5")))
        return response


def dump(url: str) -> dict[str, Any]:
    out: dict[str, Any] = {}
    with _PatientClient(base_url=url, timeout=300.0) as client:
        out["openapi"] = client.get("/openapi.json").json()
        for path in ("/api/chapters", "/api/scenes", "/api/examples", "/api/systems", "/api/bench/work-precision"):
            out[f"GET {path}"] = _answer(client.get(path))
        home = client.get("/")
        out["GET /"] = _answer(home)
        pages = sorted(set(re.findall(r'href="(/lessons/[^"#?]+)', home.text)))
        for page in [*pages, "/solver-lab", "/join", "/lessons/no-such-lesson"]:
            out[f"GET {page}"] = _answer(client.get(page))
        scenes = client.get("/api/scenes").json()
        for scene in scenes:
            sid = scene["id"]
            base = f"/api/scenes/{sid}"
            out[f"GET {base}/sessions/…"] = _answer(client.get(f"{base}/sessions/{SESSION_ID}"))
            out[f"GET {base}/sessions/…/playback"] = _answer(client.get(f"{base}/sessions/{SESSION_ID}/playback"))
            for variant in SIMULATE_VARIANTS:
                key = f"POST {base}/simulate {json.dumps(variant, sort_keys=True)}"
                out[key] = _answer(client.post(f"{base}/simulate", json=variant))
                print(key, out[key]["status"], file=sys.stderr)
        for example in client.get("/api/examples").json():
            out[f"POST /api/examples/{example['id']}/solve"] = _answer(client.post(f"/api/examples/{example['id']}/solve", json={}))
        for system in client.get("/api/systems").json():
            for formulation in system["formulations"]:
                key = f"POST /api/systems/{system['id']}/derive {formulation}"
                out[key] = _answer(client.post(f"/api/systems/{system['id']}/derive", json={"formulation": formulation}))
                n = len(system["coordinates"])
                state = [0.3 + 0.1 * i for i in range(2 * n)]
                answer = client.post(f"/api/systems/{system['id']}/rhs", json={"formulation": formulation, "state": state})
                out[f"POST /api/systems/{system['id']}/rhs {formulation}"] = _answer(answer)
                print(key, out[key]["status"], file=sys.stderr)
    return out


def compare(before_path: str, after_path: str) -> int:
    with open(before_path) as f:
        before = masked(json.load(f))
    with open(after_path) as f:
        after = masked(json.load(f))
    differences = 0
    for key in sorted(set(before) | set(after)):
        if before.get(key) != after.get(key):
            differences += 1
            a = json.dumps(before.get(key), sort_keys=True, ensure_ascii=False)
            b = json.dumps(after.get(key), sort_keys=True, ensure_ascii=False)
            first = next((i for i, (x, y) in enumerate(zip(a, b)) if x != y), min(len(a), len(b)))
            print(f"DIFFERS {key}\n  before …{html.unescape(a[max(0, first - 150):first + 150])}…"
                  f"\n  after  …{html.unescape(b[max(0, first - 150):first + 150])}…")
    print(f"{len(set(before) | set(after))} answers compared, {differences} differ")
    return 1 if differences else 0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--url", default="http://127.0.0.1:8000")
    parser.add_argument("--out")
    parser.add_argument("--compare", nargs=2, metavar=("BEFORE", "AFTER"))
    args = parser.parse_args()
    if args.compare:
        return compare(*args.compare)
    result = dump(args.url)
    with open(args.out, "w") as f:
        json.dump(result, f, sort_keys=True, ensure_ascii=False, indent=1)
    print(f"{len(result)} answers written to {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
