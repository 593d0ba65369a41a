"""Vehicles: the parametric generic compact car and its frontal load cases
(US NCAP rigid wall, Euro NCAP offset deformable barrier)."""

from .generic import GenericVehicle, generic_vehicle
from .loadcases import odb_deck, usncap_deck, vehicle_info

__all__ = ["GenericVehicle", "generic_vehicle", "odb_deck", "usncap_deck", "vehicle_info"]
