"""Example models and decks for tests, benchmarks and docs (not used by any run).

- :mod:`hollowbody.testing.models`: Models assembled from arrays (contact tests);
- :mod:`hollowbody.testing.decks`: keyword decks to convert with hollowize;
- :mod:`hollowbody.testing.engine`: the engine's own cycle driven one cycle at a time.

It sits at the top of the package layers: it may use anything, and nothing in
the package imports it.
"""
