"""Pure numerics: no viser, no FastAPI, nothing from the layers above (a test checks it).

Layers, each importing only those before it:

* :mod:`.core` — parameters, closed-form models and the simulation report, worked solutions;
* :mod:`.math` — vectors, rotations (the only implementation), expressions, curvilinear frames;
* :mod:`.solvers` — integrators (numba kernels with Python twins), their registry, events,
  constraints, step choice, and the integrated-model contract;
* :mod:`.bodies` — rigid-body data: inertia, the body about a fixed point (chapter 5 fills it);
* :mod:`.mechanics` — derivations as data (chapters 7–9 fill it);
* :mod:`.constrained` — constrained generalized coordinates: multiplier equations, the DAE algorithms, consistent starts
  (chapter 8);
* :mod:`.systems` — the physical systems, one module each, grouped by the chapter whose lessons use them.
"""
