"""sizer: actuator sizing and motion-law selection for automatic machines.

The method is chapter 6 of Biagiotti & Melchiorri, *Trajectory Planning for Automatic
Machines and Robots*: shape coefficients of normalized motion laws, torque at the motor
shaft, peak points against the intermittent region and the RMS torque against the
continuous region.
"""

__version__ = "0.1.0"
