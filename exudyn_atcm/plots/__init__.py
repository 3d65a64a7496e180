"""Plots and drawings (matplotlib, headless Agg): results, hysteresis loops, identified models,
mechanisms and their animations, cell drawings, one plot style.

May import every description and result layer; never solves anything itself.
"""
