"""The answer functions of the exercises, one module per chapter (``chNN``): each takes an exercise's given numbers
(by name, in their units) and returns every part's answer, its working and the answers of its named mistakes
(:class:`app.practice.exercise.PartAnswer`). An exercise file names its function as ``answers = "chNN.function"``.

They compute from the project's own physics where it exists (inertia tensors, the shaft-spin model, the derivation
engine's systems) and are checked in tests/practice against an independent computation.
"""
