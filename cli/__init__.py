"""Commands that sit above the packages they combine: ``cnc-plan`` (planner + PNG plots).

The planner stays free of Qt and pyqtgraph; plotting set-points to a picture is done here,
one layer up, so no lazy import has to hide a dependency from the layering contracts.
"""
