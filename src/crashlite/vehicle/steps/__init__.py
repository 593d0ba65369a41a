"""The four steps of the simplified vehicle, from the interface cut
(``cut``) on:

1. load paths through the interface (``loadpaths``);
2. mass properties of the replaced structure (``massprops``);
3. its stiffness: the linear static model (``elements``, ``statics``), held
   at the rear axle (``stiffness``) or under inertia relief (``relief``);
4. the spring–mass surrogate on the kept structure (``truncate``,
   ``surrogate``)."""
