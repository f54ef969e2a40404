"""Where a server gets a system's generated code (prepared.py): one derivation in a child per client at a time."""

from __future__ import annotations

import threading
import time

import pytest

from app.physics.core.bounded import WorkBusy
from app.physics.mechanics.multibody import prepared


def test_one_client_has_one_derivation_in_a_child_at_a_time_and_others_are_not_held_up():
    first = threading.Thread(
        target=prepared._in_child, args=(("a", "kane", "code"), time.sleep, (1.0,), "sleeping", "student-1")
    )
    first.start()
    while "student-1" not in prepared._deriving:  # wait until its place is taken
        time.sleep(0.005)
    with pytest.raises(WorkBusy) as busy:
        prepared._in_child(("b", "kane", "code"), time.sleep, (0.0,), "sleeping", "student-1")
    assert busy.value.retry_after_s > 0 and "one at a time" in str(busy.value)
    prepared._in_child(("c", "kane", "code"), time.sleep, (0.0,), "sleeping", "student-2")  # another student: runs
    first.join()
    assert "student-1" not in prepared._deriving
