"""Models: one physical system per module (parameters, state, right-hand side, invariants, references)."""
