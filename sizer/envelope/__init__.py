"""Speed-torque regions of motors (book sec. 6.1, Fig. 6.1)."""

from sizer.envelope.region import RegionTable, continuous_region, intermittent_region

__all__ = ["RegionTable", "continuous_region", "intermittent_region"]
