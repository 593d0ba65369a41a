"""Sheet materials of the generic car (mm–t–s–N–MPa).

Steels are *MAT_PIECEWISE_LINEAR_PLASTICITY (MAT_024) with a hardening
curve (true stress against effective plastic strain) of the Voce form
σ = σy + (σu,true − σy)(1 − exp(−ε/ε0)) + H ε, and Cowper–Symonds rate
factors for the rate-sensitive mild and micro-alloyed grades. Glass is
*MAT_PLASTIC_KINEMATIC (elastic, a low yield stress standing for the
cracked laminate); engine and rear axle are *MAT_RIGID with the density
that gives their mass. Yield and tensile strengths are typical catalogue
values of the grades (e.g. EN 10346 / VDA 239-100 minimums, rounded).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

STEEL_DENSITY = 7.85e-9  # t/mm³
STEEL_E = 210000.0  # MPa


@dataclass(frozen=True)
class Grade:
    name: str
    sigy: float  # yield stress [MPa]
    uts: float  # true stress reached at large strain, before the linear tail [MPa]
    c: float = 0.0  # Cowper-Symonds C [1/s] (0: rate independent)
    p: float = 0.0  # Cowper-Symonds P
    eps0: float = 0.06  # Voce saturation strain
    tail: float = 200.0  # linear hardening beyond saturation [MPa]
    density: float = STEEL_DENSITY
    e: float = STEEL_E
    pr: float = 0.3
    kind: str = "steel"  # steel (MAT_024), glass (MAT_003), rigid (MAT_020)

    def curve(self) -> tuple[np.ndarray, np.ndarray]:
        """(effective plastic strain, true stress) points of the hardening curve."""
        eps = np.array([0.0, 0.005, 0.01, 0.02, 0.04, 0.07, 0.1, 0.15, 0.2, 0.3, 0.5, 1.0])
        sig = self.sigy + (self.uts - self.sigy) * (1.0 - np.exp(-eps / self.eps0)) + self.tail * eps
        return eps, np.round(sig, 3)


GRADES = {
    g.name: g
    for g in (
        Grade("DC04", 180.0, 380.0, c=40.0, p=5.0),  # mild deep-drawing steel: skins, floor, firewall
        Grade("HX340LAD", 340.0, 520.0, c=300.0, p=4.0),  # micro-alloyed HSLA: cowl, headers, tunnel
        Grade("DP600", 380.0, 720.0, eps0=0.08),  # dual phase: crash boxes, cross members, rear rails
        Grade("DP800", 500.0, 930.0, eps0=0.07),  # dual phase: front rails, sills, hinge pillars
        Grade("MS1200", 1000.0, 1300.0, eps0=0.03, tail=100.0),  # martensitic: bumper beam
        Grade("PHS1500", 1100.0, 1550.0, eps0=0.03, tail=100.0),  # press-hardened boron: pillars, roof rails
        Grade("X2CrTi12", 280.0, 480.0, c=100.0, p=5.0),  # ferritic stainless: exhaust
        Grade("glass", 60.0, 60.0, density=2.5e-9, e=70000.0, pr=0.22, kind="glass"),  # laminated glass
        Grade("rigid", 0.0, 0.0, kind="rigid"),  # engine and gearbox, rear axle (density from the mass)
    )
}
