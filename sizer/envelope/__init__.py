"""Speed-torque regions of motors (book sec. 6.1, Fig. 6.1)."""

from sizer.envelope.completion import DEFAULT_ENVELOPE, ENVELOPE_RULES, envelope_note
from sizer.envelope.region import RegionTable, continuous_region, intermittent_region

__all__ = ["DEFAULT_ENVELOPE", "ENVELOPE_RULES", "RegionTable", "continuous_region",
           "envelope_note", "intermittent_region"]
