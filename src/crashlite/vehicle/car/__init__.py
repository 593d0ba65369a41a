"""The generic compact car and its load cases: the parametric body laid out
as lattice pieces (``body``, ``lattice``), meshed into one conforming shell
mesh (``build``) with its sheet materials (``materials``) and mass trim
(``trim``), assembled as a keyword Model (``generic``, with the keyword
records of ``records``), and the frontal load cases it runs in
(``loadcases``: US NCAP rigid wall, Euro NCAP offset deformable barrier)."""
