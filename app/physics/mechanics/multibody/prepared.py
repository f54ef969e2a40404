"""A system built of parts, prepared for a server: its generated code loaded, derived first in a bounded child.

Deriving is sympy work whose time grows fast with the system: a 20-link chain takes about 2 s by Kane's method and
minutes by Lagrange's from the energies; a described system is whatever its author made it. A server therefore
never derives in its own process. :func:`prepared` loads the generated code if any process derived it before (from
memory or the disk cache, :func:`~.compiled.loaded`); otherwise it derives it in a child of the typed-Lagrangian
runner (time and memory limits; a 429 when every place is taken, :mod:`app.physics.core.bounded`), which writes the
code to the disk cache, and then loads it. A derivation that ran into its limits is remembered and refused at once
for :data:`REFUSED_KEPT_S`, so asking again does not spend another :data:`DERIVE_TIMEOUT_S` of a processor; and one
client (an address) has at most one derivation in a child at a time, so one student cannot take every place.

A described system (:mod:`.data`) is anyone's: its code is loaded privately, and only the last
:data:`DESCRIBED_KEPT` are kept in this process.
"""

from __future__ import annotations

import hashlib
import threading
import time
from collections import OrderedDict
from collections.abc import Callable, Mapping
from typing import Any

from app.physics.core.bounded import WorkBusy, WorkInterrupted, WorkRefused, WorkTimeout, WorkTooLarge
from app.physics.mechanics import typed
from app.physics.mechanics.multibody import shown
from app.physics.mechanics.multibody.compiled import CompiledSystem, compiled, loaded
from app.physics.mechanics.multibody.data import system_from_data
from app.physics.mechanics.multibody.parts import MultibodySystem

#: How long a first derivation may take in its child (s): a spatial 10-link chain takes about 5 s by Kane's method
#: on an idle machine (15 s with its LaTeX); Lagrange's equations of a long chain take far longer and are refused.
DERIVE_TIMEOUT_S = 45.0
#: A derivation that ran into its limits is refused again at once for this long (s).
REFUSED_KEPT_S = 600.0
#: Described systems' generated functions kept in this process.
DESCRIBED_KEPT = 16

_refused: dict[tuple[str, str, str], tuple[float, WorkRefused]] = {}
#: Clients with a derivation in a child now.
_deriving: set[str] = set()
_described: OrderedDict[str, CompiledSystem] = OrderedDict()
_lock = threading.Lock()


#: Finds a catalogue system's member by id and parameters, in the child: a module-level function of the catalogue's
#: layer (app.physics.systems.multibody_member), passed down and pickled by reference, since mechanics imports nothing
#: above it.
MemberOf = Callable[[str, Mapping[str, Any]], MultibodySystem]


def _derive_member(member_of: MemberOf, system_id: str, params: Mapping[str, Any], formulation: str) -> dict[str, Any]:
    """In the child: derive the catalogue system's member for ``params`` and write its code to the disk cache."""
    model = compiled(member_of(system_id, params), formulation=formulation)
    return {"derive_s": model.derive_s, "generate_s": model.generate_s}


def _derive_described(data: Mapping[str, Any], root: str) -> dict[str, Any]:
    """In the child: build the described system, derive it by Kane's method and write its code to the disk cache."""
    model = compiled(system_from_data(data, root=root))
    return {"derive_s": model.derive_s, "generate_s": model.generate_s}


def _in_child(
    key: tuple[str, str, str], function: Callable[..., Any], arguments: tuple, what: str, client: str | None
) -> Any:
    """``function(*arguments)`` in a bounded child, unless the same work ran into its limits lately or ``client``
    already has a derivation running (WorkBusy: a 429)."""
    with _lock:
        refused = _refused.get(key)
        if refused is not None and time.monotonic() - refused[0] < REFUSED_KEPT_S:
            raise refused[1]
        if client is not None and client in _deriving:
            raise WorkBusy(
                "you already have a derivation running; one at a time each, so everyone gets a place",
                retry_after_s=int(DERIVE_TIMEOUT_S),
            )
        if client is not None:
            _deriving.add(client)
    try:
        return typed.runner.run(function, arguments, timeout_s=DERIVE_TIMEOUT_S, what=what)
    except (WorkTimeout, WorkTooLarge) as error:
        with _lock:
            _refused[key] = (time.monotonic(), error)
        raise
    finally:
        if client is not None:
            with _lock:
                _deriving.discard(client)


def refused_before(key: tuple[str, str, str]) -> None:
    """Raise the remembered refusal for ``key`` if the same work ran into its limits lately (else nothing)."""
    with _lock:
        refused = _refused.get(key)
    if refused is not None and time.monotonic() - refused[0] < REFUSED_KEPT_S:
        raise refused[1]


def prepared(
    member_of: MemberOf,
    system_id: str,
    params: Mapping[str, Any],
    system: MultibodySystem,
    formulation: str,
    *,
    client: str | None = None,
) -> CompiledSystem:
    """The generated functions of ``system``, the catalogue entry ``system_id``'s member for the validated
    ``params``: loaded, after deriving them in a bounded child if no process has yet."""
    found = loaded(system, formulation=formulation)
    if found is not None:
        return found
    key = (system.fingerprint(), formulation, "code")
    arguments = (member_of, system_id, dict(params), formulation)
    _in_child(key, _derive_member, arguments, f"deriving {system.title} by {formulation}", client)
    found = loaded(system, formulation=formulation)
    if found is None:  # the child wrote it; another process's cleaning may have removed it since
        raise WorkInterrupted("the derived code was not found where it was written; try again", signal_number=0)
    return found


def description_key(text: str) -> tuple[str, str, str]:
    """The refusal key of a description, from its text (the request's JSON or TOML): checked before it is read."""
    return (hashlib.sha256(text.encode()).hexdigest()[:32], "kane", "described")


def prepared_description(
    data: Mapping[str, Any], root: str, system: MultibodySystem, *, text: str, client: str | None = None
) -> tuple[CompiledSystem, bool]:
    """A described system's generated functions, and whether they were derived for this call (else: cached).
    ``text`` is the request's own form of it (see :func:`description_key`)."""
    key = system.fingerprint()
    with _lock:
        found = _described.get(key)
        if found is not None:
            _described.move_to_end(key)
            return found, False
    derived_now = False
    model = loaded(system, keep=False)
    if model is None:
        _in_child(description_key(text), _derive_described, (dict(data), root), "deriving this system", client)
        derived_now = True
        model = loaded(system, keep=False)
        if model is None:
            raise WorkInterrupted("the derived code was not found where it was written; try again", signal_number=0)
    with _lock:
        _described[key] = model
        while len(_described) > DESCRIBED_KEPT:
            _described.popitem(last=False)
    return model, derived_now


def shown_derivation(
    member_of: MemberOf,
    system_id: str,
    params: Mapping[str, Any],
    system: MultibodySystem,
    formulation: str,
    *,
    client: str | None = None,
) -> dict[str, Any]:
    """The derive route's body (:mod:`.shown`): from memory or the disk cache, else derived in a bounded child."""
    found = shown.shown_cached(system, formulation)
    if found is not None:
        return {**found, "derive_s": 0.0, "compile_s": 0.0, "cached": True}
    key = (system.fingerprint(), formulation, "shown")
    arguments = (member_of, system_id, dict(params), formulation)
    return _in_child(key, shown.derive_shown, arguments, f"deriving {system.title} by {formulation}", client)
