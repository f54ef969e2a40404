"""Mathematics the systems share: vectors, rotations (the only implementation), expressions, curvilinear frames."""
