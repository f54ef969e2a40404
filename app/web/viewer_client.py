"""viser's client, unpacked once on the server: its page loads viser's script and style as two files the browser
fetches and compiles off the page's main thread and then keeps, instead of unpacking them in every viewer.

viser 1.1.1 ships ``client/build/index.html`` as one loader script whose ``data-p`` attribute holds the client's style
and script (2.6 MB), zstd-compressed and base-88 encoded. The loader decodes them in JavaScript, decompresses them
with a zstd WebAssembly module it carries, and runs the script as an inline module: all on the viewer's main thread,
which a lesson page's viewer shares with the page. Here the same bytes are decoded and decompressed once, in Python
(``zstandard`` is viser's own dependency). The page keeps the loader's WebAssembly part (the client decodes
zstd-compressed messages with the module the loader publishes as ``globalThis.__viserZstdWasm``) and then runs the
script from :data:`SCRIPT_URL`, which it preloads as the page is parsed. Both files are gzip-compressed (fewer bytes
than the single file for every viewer after a browser's first) and cached for a year: their URLs name viser's version.
"""

from __future__ import annotations

import gzip
import html
import re
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import numpy as np
import viser
import zstandard
from fastapi import APIRouter, HTTPException, Request
from fastapi.responses import Response

router = APIRouter(tags=["pages"], include_in_schema=False)

#: viser's client files, by version: a new viser gets new URLs, so a browser never keeps a stale one.
SCRIPT_URL = f"/viewer-client/viser-{viser.__version__}.js"
STYLE_URL = f"/viewer-client/viser-{viser.__version__}.css"
_CACHED_A_YEAR = "public, max-age=31536000, immutable"

#: viser's base-88 alphabet (the loader's ``A``): five characters carry four bytes, big-endian.
_BASE88 = "!#$%()*+,-./0123456789:;=?@ABCDEFGHIJKLMNOPQRSTUVWXYZ[\\]^_abcdefghijklmnopqrstuvwxyz{|}~"
_PACKED = re.compile(r'<script data-p="([^"]*)" data-ss="(\d+)" data-cs="(\d+)">(.*?)</script>', re.DOTALL)
#: Where the loader has its WebAssembly ready and goes on to unpack the client: what follows is replaced.
_WASM_READY = "await init();"


@dataclass(frozen=True)
class UnpackedClient:
    """viser's client page with its loader cut to the WebAssembly part, and the client's files (gzip-compressed)."""

    page: bytes
    script_gz: bytes
    style_gz: bytes


def _base88_decode(text: str) -> bytes:
    """The loader's ``de``: each five characters are four bytes (big-endian); a final group of r characters is r − 1
    bytes."""
    digit = np.zeros(128, dtype=np.uint64)
    digit[np.frombuffer(_BASE88.encode("ascii"), dtype=np.uint8)] = np.arange(88, dtype=np.uint64)
    codes = digit[np.frombuffer(text.encode("ascii"), dtype=np.uint8)]
    whole, rest = divmod(len(codes), 5)
    values = np.zeros(whole, dtype=np.uint64)
    for column in codes[: whole * 5].reshape(whole, 5).T:
        values = values * 88 + column
    out = values.astype(">u4").tobytes()
    if rest > 1:
        value = 0
        for code in codes[whole * 5 :]:
            value = value * 88 + int(code)
        out += value.to_bytes(rest - 1, "big")
    return out


def _runs_script() -> str:
    """JavaScript that runs the client's script once the page is parsed, as viser's loader runs its inline copy."""
    return (
        'const run=()=>{const e=document.createElement("script");e.type="module";'
        f'e.src="{SCRIPT_URL}";document.head.appendChild(e);}};'
        'if(document.readyState==="loading"){document.addEventListener("DOMContentLoaded",run);}else{run();}})();'
    )


@cache
def unpacked_client() -> UnpackedClient:
    """viser's ``client/build/index.html``, unpacked (about 0.1 s, once per process)."""
    client = (Path(viser.__file__).resolve().parent / "client" / "build" / "index.html").read_text(encoding="utf-8")
    found = list(_PACKED.finditer(client))
    loader = found[0].group(4) if len(found) == 1 else ""
    if loader.count(_WASM_READY) != 1:
        raise RuntimeError(f"viser {viser.__version__}'s client page is not the single-file loader this module unpacks")
    packed, style_size, script_size = found[0].group(1, 2, 3)
    raw = zstandard.ZstdDecompressor().decompress(
        _base88_decode(html.unescape(packed)), max_output_size=int(style_size) + int(script_size)
    )
    style, script = raw[: int(style_size)], raw[int(style_size) :]
    if len(script) != int(script_size):
        raise RuntimeError(f"viser {viser.__version__}'s client unpacked to {len(raw)} bytes, not the sizes it states")
    head = f'<link rel="modulepreload" href="{SCRIPT_URL}"><link rel="stylesheet" href="{STYLE_URL}">'
    wasm_only = loader[: loader.index(_WASM_READY) + len(_WASM_READY)] + _runs_script()
    page = client[: found[0].start()] + f"{head}<script>{wasm_only}</script>" + client[found[0].end() :]
    squeeze = lambda data: gzip.compress(data, compresslevel=6, mtime=0)  # noqa: E731
    return UnpackedClient(page=page.encode(), script_gz=squeeze(script), style_gz=squeeze(style))


@router.get("/viewer-client/{name}")
def viewer_client_file(name: str, request: Request) -> Response:
    """viser's client script or style (:data:`SCRIPT_URL`, :data:`STYLE_URL`), gzip-compressed when the browser takes
    it (every browser does), cached for a year."""
    files = {
        SCRIPT_URL: ("text/javascript; charset=utf-8", unpacked_client().script_gz),
        STYLE_URL: ("text/css; charset=utf-8", unpacked_client().style_gz),
    }
    found = files.get(f"/viewer-client/{name}")
    if found is None:
        raise HTTPException(status_code=404, detail=f"no viewer client file {name!r}")
    media_type, body = found
    headers = {"Cache-Control": _CACHED_A_YEAR, "Vary": "Accept-Encoding"}
    if "gzip" in request.headers.get("accept-encoding", ""):
        return Response(body, media_type=media_type, headers={**headers, "Content-Encoding": "gzip"})
    return Response(gzip.decompress(body), media_type=media_type, headers=headers)
