"""How the surrogate joins the kept structure to the replaced rear, and what
that costs, beyond the paper's four steps: the connection's 6×6 against
the structure's (``connection``), the rear's vibration modes (``modes``),
the replaced structure condensed onto the cut (``condense``,
``condensed``) with its wave impedance (``impedance``), the elastic twin
that measures the premise (``twin``), where to put the interface
(``interface``) and the rigid fit that measures a cut's warping
(``rigidfit``)."""
