"""Railpad models: complex dynamic stiffness K*(f, T) of one rail seat, in N/m."""

from railvib.pads.base import PadModel
from railvib.pads.simple import ConstantPhase, Hysteretic, LogLinear, SpringDamper

__all__ = ["ConstantPhase", "Hysteretic", "LogLinear", "PadModel", "SpringDamper"]
