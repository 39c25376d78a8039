import os
from typing import Any, Mapping, Optional, Union

from . import _palp

RecordingLike = Union[str, os.PathLike[str], _palp.Recording, Mapping[str, Any]]

def recording(source: RecordingLike) -> _palp.Recording: ...
def indentation(source: RecordingLike, params: Optional[_palp.IndentationParams] = ...) -> dict[str, Any]: ...
def to_pandas(source: RecordingLike) -> Any: ...
