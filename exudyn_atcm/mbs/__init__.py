"""The Exudyn layer of mechanisms: building a :class:`~exudyn_atcm.mechanism.Mechanism` into a
``MainSystem``, step hooks shared with user code, read-outs and linearisation.

With :mod:`exudyn_atcm._mbs_builder` this is the only part of the package that calls Exudyn.
"""
