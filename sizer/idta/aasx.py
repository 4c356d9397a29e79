"""The IDTA 02021 submodel in an AASX package (ECMA-376 Part 2 / OPC, AAS Part 5), made by
basyx-python-sdk (the ``aas`` extra: ``pip install 'sizer-motion[aas]'``), imported here only.

The package holds the environment ``{"submodels": [submodel]}`` (no shell: sizer knows no
asset) as one JSON part, ``/aasx/data.json``, read by basyx's JSON reader and written by its
AASXWriter (basyx re-serializes it: ``2026-12-06T16:00:00Z`` becomes ``...+00:00``, the same
instant). The same submodel gives the same bytes: every ZIP entry is re-stamped 1980-01-01
(the ZIP epoch; the date is in the submodel and in the package's core properties) and the
entries keep basyx's order.
"""

from __future__ import annotations

import io
import json
import zipfile
from datetime import datetime
from typing import Any

AAS_EXTRA = "aas"
INSTALL_HINT = f"pip install 'sizer-motion[{AAS_EXTRA}]'"
PART = "/aasx/data.json"
"""The package's AAS part (JSON)."""
ZIP_EPOCH = (1980, 1, 1, 0, 0, 0)


class AasxUnavailableError(RuntimeError):
    """basyx-python-sdk is not installed (the ``aas`` extra)."""


def aasx_available() -> bool:
    """Whether basyx-python-sdk can be imported."""
    try:
        import basyx.aas.adapter.aasx  # noqa: F401
    except ImportError:
        return False
    return True


def aasx_package(submodel: dict[str, Any], *, created: datetime, creator: str) -> bytes:
    """The AASX package (bytes) of the environment holding ``submodel`` (AAS V3.0 JSON, as
    :func:`sizer.idta.write.sizing_result_submodel` gives it); ``created`` (timezone-aware)
    and ``creator`` go to the package's core properties. AasxUnavailableError without basyx;
    ValueError (basyx's) for a submodel that is not valid AAS."""
    try:
        import pyecma376_2
        from basyx.aas.adapter import aasx
        from basyx.aas.adapter.json import read_aas_json_file
    except ImportError as error:
        raise AasxUnavailableError(
            f"writing AASX needs basyx-python-sdk: {INSTALL_HINT}") from error
    environment = json.dumps({"submodels": [submodel]})
    store = read_aas_json_file(io.StringIO(environment), failsafe=False)
    buffer = io.BytesIO()
    with aasx.AASXWriter(buffer, failsafe=False) as writer:
        writer.write_all_aas_objects(PART, store, aasx.DictSupplementaryFileContainer(),
                                     write_json=True)
        properties = pyecma376_2.OPCCoreProperties()
        properties.creator = creator
        properties.created = created
        properties.modified = created
        writer.write_core_properties(properties)
    return _restamped(buffer.getvalue())


def _restamped(package: bytes) -> bytes:
    """``package`` with every entry dated ZIP_EPOCH, in the same order, deflated: how
    ``zipfile`` dates the entries basyx opens by name is no documented promise."""
    out = io.BytesIO()
    with zipfile.ZipFile(io.BytesIO(package)) as source, \
            zipfile.ZipFile(out, "w", compression=zipfile.ZIP_DEFLATED) as target:
        for entry in source.infolist():
            info = zipfile.ZipInfo(entry.filename, date_time=ZIP_EPOCH)
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o644 << 16
            target.writestr(info, source.read(entry))
    return out.getvalue()
