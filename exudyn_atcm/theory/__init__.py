"""Closed-form and semi-analytic references: composite beam theory, the elastica, the rigid four-bar
and the assumed-modes (Rayleigh-Ritz) mathematics of the ``ritz`` cell.

May import: numpy, scipy and the package's argument checks only.
"""
