"""What the cell choice hands its stand-in: a spy on ``cell_choice.frequency_error_share`` (a test helper)."""

from __future__ import annotations

from exudyn_atcm.solve import cell_choice


def spy_frequency_error_share(monkeypatch) -> list[tuple[float, float]]:
    """Patch ``cell_choice.frequency_error_share`` to record ``(frequency [Hz], damping ratio [-])`` of each call (the
    list returned, filled as the choice runs) and return what the original returns."""
    seen: list[tuple[float, float]] = []
    original = cell_choice.frequency_error_share

    def spy(mech, t_end, frequency, delta, zeta, strains=None):
        seen.append((frequency, zeta))
        return original(mech, t_end, frequency, delta, zeta, strains)
    monkeypatch.setattr(cell_choice, "frequency_error_share", spy)
    return seen
