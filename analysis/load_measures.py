"""The units' fluid loads of two runs of one layer and sea, compared.

Description
    The measures bench/run_stability_speed.sh and bench/compare_damage.py
    report (docs/validation/speed.md, the refined mesh). Loads are arrays
    (records, units, 3) in N over the same records of both runs; each unit's
    changing part is its load less its mean over the window (the buoyancy
    both share left out).
        time_series_difference  rms of b - a over the rms of a's changing part
        intensity               each unit's rms swing about its mean, N
        intensity_difference    unit by unit, rms of the intensities' differences
                                over the rms of a's intensities: blind to when
                                a wave breaks, which the time series is not

Usage
    from load_measures import intensity, intensity_difference, time_series_difference
    intensity_difference(forces_a, forces_b)   # 0.029: 2.9 %
"""
import numpy as np


def swings(f):
    """Each record's swing of each unit's load about its mean over the window, N: (records, units)."""
    return np.linalg.norm(f - f.mean(axis=0), axis=2)


def intensity(f):
    """Each unit's rms swing about its mean over the window, N: (units,)."""
    return np.sqrt((swings(f) ** 2).mean(axis=0))


def intensity_difference(a, b):
    ia, ib = intensity(a), intensity(b)
    return float(np.sqrt(((ib - ia) ** 2).mean()) / np.sqrt((ia**2).mean()))


def time_series_difference(a, b):
    return float(np.sqrt(((b - a) ** 2).sum(axis=2).mean()) / np.sqrt((swings(a) ** 2).mean()))
