"""Every use of viser's private API, in one place (checked against viser 1.1.1, pinned).

viser 1.1.1 lacks three things the scenes need, so these functions reach into
its private modules: a per-client initial camera (viser sets one only
server-wide), the request path of a client's websocket (the host reads the
scene and session ids from it), and the encoded first message a browser's
viewer sends (tests stand in for a browser with it). The names of nodes on a
scene API are read for tests that check a scene removed what it built.
``tests/scenes/host/test_viser_compat.py`` pins the version and checks each
function against a real loopback server: re-check them all when viser is
upgraded. Nothing else in ``app/`` or ``tests/`` may import ``viser._*`` or
touch a ``_websock*`` attribute (a test greps for it).
"""

from __future__ import annotations

import msgspec
import viser
from viser import _messages
from viser._viser import InitialCameraConfig

#: The viser version these private calls were checked against.
CHECKED_VISER_VERSION = "1.1.1"


def set_initial_camera(
    client: viser.ClientHandle, *, position: tuple[float, float, float], look_at: tuple[float, float, float]
) -> None:
    """Make ``position`` / ``look_at`` (m, world frame, +Z up) this viewer's start pose and "Reset View" target.

    The message is addressed to this client only, so it never moves another
    student's camera, nor this student's current one.
    """
    initial = InitialCameraConfig(client._websock_connection.queue_message)
    initial.look_at = look_at
    initial.position = position


def connection_path(server: viser.ViserServer, client: viser.ClientHandle) -> str | None:
    """The request path (with any query) of ``client``'s websocket, or None once it has gone."""
    connection = server._websock_server._live_connections.get(client.client_id)
    return None if connection is None else connection.request.path


def viewer_camera_message(
    *, position: tuple[float, float, float] = (3.0, -3.0, 2.0), look_at: tuple[float, float, float] = (0.0, 0.0, 0.0)
) -> bytes:
    """The encoded camera message a browser's viewer sends first; viser counts a client as connected only after it."""
    camera = _messages.ViewerCameraMessage(
        wxyz=(1.0, 0.0, 0.0, 0.0), position=position, fov=1.0, near=0.01, far=100.0,
        image_height=480, image_width=640, look_at=look_at, up_direction=(0.0, 0.0, 1.0),
    )  # fmt: skip
    return msgspec.msgpack.encode(camera.as_serializable_dict())


def scene_node_names(scene: viser.SceneApi) -> set[str]:
    """Names of the nodes currently on ``scene`` (a client's or the server's scene API)."""
    return {name for name, handle in scene._handle_from_node_name.items() if not handle._impl.removed}
