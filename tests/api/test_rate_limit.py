"""Token buckets: a burst at once, then the rate; each client apart; the table bounded, oldest forgotten first."""

from __future__ import annotations

import pytest

from app.api.rate_limit import TokenBuckets


def buckets(*, burst=3, rate_per_s=2.0, max_clients=100):
    now = [0.0]
    return TokenBuckets(burst=burst, rate_per_s=rate_per_s, max_clients=max_clients, clock=lambda: now[0]), now


def test_a_burst_then_the_wait_until_the_next_token():
    limit, now = buckets(burst=3, rate_per_s=2.0)
    assert [limit.take("a") for _ in range(3)] == [0.0, 0.0, 0.0]
    assert limit.take("a") == pytest.approx(0.5)  # one token every 1/2 s; exact arithmetic on a frozen clock
    now[0] = 0.25
    assert limit.take("a") == pytest.approx(0.25)  # half a token back: half the wait left
    now[0] = 0.5
    assert limit.take("a") == 0.0


def test_a_long_pause_refills_at_most_the_burst():
    limit, now = buckets(burst=3, rate_per_s=2.0)
    for _ in range(3):
        limit.take("a")
    now[0] = 1000.0
    assert [limit.take("a") for _ in range(4)][-1] > 0  # three back, not two thousand


def test_clients_have_their_own_buckets():
    limit, _ = buckets(burst=1)
    assert limit.take("a") == 0.0 and limit.take("a") > 0
    assert limit.take("b") == 0.0


def test_the_table_is_bounded_and_forgets_the_least_recently_seen_client():
    limit, _ = buckets(burst=1, max_clients=3)
    for client in ("a", "b", "c"):
        limit.take(client)
    limit.take("a")  # a was seen again: b is now the oldest
    limit.take("d")
    assert len(limit) == 3
    assert limit.take("b") == 0.0  # forgotten, so a full bucket again
    assert limit.take("a") > 0  # remembered: still empty


def test_burst_zero_means_no_limit():
    limit, _ = buckets(burst=0)
    assert {limit.take("a") for _ in range(1000)} == {0.0}
    assert len(limit) == 0


@pytest.mark.parametrize(("burst", "rate_per_s", "max_clients"), [(-1, 1.0, 1), (1, 0.0, 1), (1, float("nan"), 1), (1, float("inf"), 1), (1, 1.0, 0)])
def test_bad_limits_are_refused(burst, rate_per_s, max_clients):
    with pytest.raises(ValueError):
        TokenBuckets(burst=burst, rate_per_s=rate_per_s, max_clients=max_clients)
