"""Vehicles: the parametric generic compact car and its frontal load cases
(US NCAP rigid wall, Euro NCAP offset deformable barrier), and the
simplified-vehicle method on it, one sub-package per part of the method:

- ``car``: the generic car (body, lattice, mesh, materials, mass trim,
  keyword records) and its load cases;
- ``steps``: the interface cut and the four steps (load paths, mass
  properties, stiffness, the spring–mass surrogate);
- ``connection``: how the surrogate joins the kept structure to the rear,
  and what that costs (connection stiffness, modes, condensed structure,
  impedance, elastic twin, where to put the interface);
- ``verify``: the simplified vehicle against its full model, and the pages
  of a verification, a reduction and the paper study;
- ``reduce`` (the four steps from a full deck and its runs) and
  ``workflow`` (the paper's workflow on the generic car, end to end).
"""

from .car.generic import GenericVehicle, generic_vehicle
from .car.loadcases import odb_deck, usncap_deck, vehicle_info

__all__ = ["GenericVehicle", "generic_vehicle", "odb_deck", "usncap_deck", "vehicle_info"]
