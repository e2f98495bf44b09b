"""Material pairs and load cases of the thesis's asperity-scale experiments.

Data only (Tables 3.1-3.4 of Eriten 2012, after Varenberg et al.); the physics is in
the C++ library. SI units.
"""
from __future__ import annotations

from ._core import ContactPair, FrictionParameters, Material

#: Table 3.1: bearing-steel ball (SAE 52100, 60 HRC) and hardened steel flat (63 HRC).
MICRO_BALL = dict(E=207e9, nu=0.3, G=82.7e9, H=6.83e9)
MICRO_FLAT = dict(E=207e9, nu=0.3, G=82.7e9, H=7.48e9)
#: Sphere radius of Table 3.1 [m].
MICRO_R = 2.5e-3
#: CFC friction coefficient used in chapter 3: AISI 304N, s/H = 186/655 MPa (Eq. 3.13).
MICRO_MU_CFC = 0.284
#: Table 3.2: (P [N], delta_max [m]) of micro-scale experiments 1 and 2.
MICRO_EXPERIMENTS = ((35.0, 1.5e-6), (23.0, 10e-6))

#: Table 3.3: silica microsphere on a silicon (100) flat.
NANO_SPHERE = dict(E=68.0e9, nu=0.19, G=28.0e9, H=4.8e9)
NANO_FLAT = dict(E=112.4e9, nu=0.28, G=43.9e9, H=11.3e9)
NANO_R = 1.55e-6
#: CFC friction coefficient of silica used for Table 3.4.
NANO_MU_CFC = 0.259
#: Table 3.4: (P [N], delta_max [m]) of nano-scale experiments 1 and 2.
NANO_EXPERIMENTS = ((1.1e-6, 5e-9), (1.2e-6, 15e-9))


def micro_pair() -> ContactPair:
    """Combined properties of Table 3.1 (steel ball R = 2.5 mm on a steel flat)."""
    return ContactPair.combine(Material(**MICRO_BALL), Material(**MICRO_FLAT), MICRO_R)


def micro_params() -> FrictionParameters:
    """Friction parameters of chapter 3's micro-scale case (mu_cfc = 0.284)."""
    return FrictionParameters(mu_cfc=MICRO_MU_CFC)


def nano_pair() -> ContactPair:
    """Combined properties of Table 3.3 (silica sphere R = 1.55 um on silicon)."""
    return ContactPair.combine(Material(**NANO_SPHERE), Material(**NANO_FLAT), NANO_R)


def nano_params() -> FrictionParameters:
    """Friction parameters of chapter 3's nano-scale case (mu_cfc = 0.259)."""
    return FrictionParameters(mu_cfc=NANO_MU_CFC)
