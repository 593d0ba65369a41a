"""The keyword catalogue: importing this package registers every schema.

One module per family. Field names follow the LS-DYNA keyword manual in
lower case (``secid``, ``ro``, ``sigy``), so users find them where the
manual puts them.
"""

from . import bc, constraints, contacts, controls, defines, mat, mesh, parts, setdefs  # noqa: F401
