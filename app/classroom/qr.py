"""A room's join address as a QR code (SVG) for the projector: a phone's camera opens it.

segno (pure Python, no dependencies) encodes it: a correct QR encoder is
Reed–Solomon coding, eight masks and their penalty rules, which is far more
than this one picture is worth writing by hand.
"""

from __future__ import annotations

import io

import segno


def qr_svg(text: str, *, scale: int = 8) -> bytes:
    """``text`` as a QR code (error correction M, dark on white, a 4-module quiet zone), SVG bytes."""
    code = segno.make(text, error="m", micro=False)
    out = io.BytesIO()
    code.save(
        out,
        kind="svg",
        scale=scale,
        border=4,
        dark="#111",
        light="#fff",
        xmldecl=False,
        svgns=True,
        title="Join this room",
    )
    return out.getvalue()
