"""A bounded property-based fuzz of the whole HTTP API against ``dynlab serve``: no request gets a 5xx.

schemathesis generates requests (valid and invalid) for every operation in the OpenAPI document and
sends them over HTTP to the served app with its scene workers (tests/served.py), each case from a
loopback address of its own (a new device: the per-device limits are tested elsewhere; the fuzz is
for what reaches the routes and the workers). The default run is small enough for CI and
derandomized, so a failure reproduces; the long run is

    DYNLAB_FUZZ_EXAMPLES=500 python3 -m uv run --group test pytest tests/api/test_fuzz.py -p no:cacheprovider -n 0

(500 cases for each of the 30 operations, fewer where one takes little input: 11 507 in all on 2026-11-28, no 5xx, 2 minutes). The viewer websocket is not in
OpenAPI; tests/api/test_access.py and tests/web/test_guard.py cover its refusals.
"""

from __future__ import annotations

import itertools
import os

import pytest
import requests
import schemathesis
from hypothesis import HealthCheck, settings
from requests.adapters import HTTPAdapter
from schemathesis.checks import not_a_server_error

from app.main import create_app
from app.scenes import SCENES

#: Cases per operation. Small by default; DYNLAB_FUZZ_EXAMPLES for a long run.
EXAMPLES = int(os.environ.get("DYNLAB_FUZZ_EXAMPLES", "60"))
APP = create_app()  # only for its OpenAPI document: the requests go to the served app
SCHEMA = schemathesis.openapi.from_dict(APP.openapi())
#: Real ids: the document cannot list them, and a random id only ever meets the 404.
KNOWN_IDS = {
    "scene_id": sorted(SCENES),
    "example_id": sorted(APP.state.catalogue.examples),
    "exercise_id": sorted(APP.state.exercises.exercises),
}
_devices = itertools.count(1)


@SCHEMA.hook("map_path_parameters")
def real_ids_half_the_time(ctx, path_parameters):
    """Replace a drawn scene or example id of even length by a real one (picked from its characters: reproducible)."""
    for name, known in KNOWN_IDS.items():
        value = (path_parameters or {}).get(name)
        if isinstance(value, str) and len(value) % 2 == 0:
            path_parameters[name] = known[sum(map(ord, value)) % len(known)]
    return path_parameters


class SourceAddress(HTTPAdapter):
    """Connections that leave from one loopback address (one device)."""

    def __init__(self, address: str) -> None:
        self.address = address
        super().__init__()

    def init_poolmanager(self, *args, **kwargs):
        kwargs["source_address"] = (self.address, 0)
        return super().init_poolmanager(*args, **kwargs)


def device_session() -> requests.Session:
    n = next(_devices)
    session = requests.Session()
    session.mount("http://", SourceAddress(f"127.3.{n // 250 % 250}.{n % 250 + 1}"))
    return session


@pytest.fixture(scope="module")
def served_url(served) -> str:
    return served.url


@SCHEMA.parametrize()
@settings(max_examples=EXAMPLES, deadline=None, derandomize=True, suppress_health_check=list(HealthCheck))
def test_no_request_is_a_server_error(case, served_url):
    with device_session() as session:
        case.call_and_validate(base_url=served_url, session=session, checks=[not_a_server_error], timeout=60)
