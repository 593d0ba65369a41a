"""Public functions and methods of the public API carry type annotations
(issue 32): every parameter (except self/cls, *args and **kwargs) and the
return of each public function, and of each public method of a public
class, defined in the modules below. Names imported from other modules and
Numba dispatchers are skipped."""

from __future__ import annotations

import importlib
import inspect

import pytest

MODULES = [
    # the names crashlite/__init__.py exports, and the modules they live in
    "crashlite",
    "crashlite.keyword.errors",
    "crashlite.keyword.reader",
    "crashlite.keyword.writer",
    "crashlite.model.model",
    "crashlite.results",
    "crashlite.results.history",
    "crashlite.results.folder",
    "crashlite.results.ascii",
    "crashlite.results.vtk",
    "crashlite.results.d3plot",
    "crashlite.results.from_history",
    "crashlite.results.openradioss_th",
    "crashlite.verify",
    "crashlite.verify.compare",
    "crashlite.verify.curves",
    "crashlite.verify.errors",
    "crashlite.verify.fields",
    "crashlite.verify.filters",
    "crashlite.verify.pulse",
    "crashlite.verify.rating",
    "crashlite.verify.timing",
    "crashlite.barrier",
    "crashlite.barrier.calibrate",
    "crashlite.barrier.cases",
    "crashlite.barrier.characterise",
    "crashlite.barrier.detailed",
    "crashlite.barrier.loadcases",
    "crashlite.barrier.report",
    "crashlite.barrier.simplified",
    "crashlite.barrier.spec",
    "crashlite.barrier.verify",
    "crashlite.study",
    "crashlite.study.config",
    "crashlite.study.runner",
    "crashlite.study.responses",
    "crashlite.external",
    # the solver (its Numba kernels in solver/kernels left out)
    "crashlite.solver",
    "crashlite.solver.beams",
    "crashlite.solver.boundary",
    "crashlite.solver.contact",
    "crashlite.solver.contact_build",
    "crashlite.solver.discretes",
    "crashlite.solver.frames",
    "crashlite.solver.groups",
    "crashlite.solver.initial",
    "crashlite.solver.loads",
    "crashlite.solver.loop",
    "crashlite.solver.massless",
    "crashlite.solver.motions",
    "crashlite.solver.nodal_bodies",
    "crashlite.solver.parts",
    "crashlite.solver.penetrations",
    "crashlite.solver.records",
    "crashlite.solver.results",
    "crashlite.solver.rigid",
    "crashlite.solver.rigid_parts",
    "crashlite.solver.sections",
    "crashlite.solver.setup",
    "crashlite.solver.shells",
    "crashlite.solver.solids",
    "crashlite.solver.spotwelds",
    "crashlite.solver.state",
    "crashlite.solver.superelement",
    "crashlite.solver.support",
    "crashlite.solver.tied",
    "crashlite.solver.timestep",
    "crashlite.solver.walls",
    # vehicle reduction: the generic car, the steps, the connection, the verification
    "crashlite.vehicle",
    "crashlite.vehicle.car",
    "crashlite.vehicle.car.body",
    "crashlite.vehicle.car.build",
    "crashlite.vehicle.car.generic",
    "crashlite.vehicle.car.lattice",
    "crashlite.vehicle.car.loadcases",
    "crashlite.vehicle.car.materials",
    "crashlite.vehicle.car.records",
    "crashlite.vehicle.car.trim",
    "crashlite.vehicle.connection",
    "crashlite.vehicle.connection.condense",
    "crashlite.vehicle.connection.condensed",
    "crashlite.vehicle.connection.connection",
    "crashlite.vehicle.connection.impedance",
    "crashlite.vehicle.connection.interface",
    "crashlite.vehicle.connection.modes",
    "crashlite.vehicle.connection.rigidfit",
    "crashlite.vehicle.connection.twin",
    "crashlite.vehicle.reduce",
    "crashlite.vehicle.steps",
    "crashlite.vehicle.steps.cut",
    "crashlite.vehicle.steps.elements",
    "crashlite.vehicle.steps.loadpaths",
    "crashlite.vehicle.steps.massprops",
    "crashlite.vehicle.steps.relief",
    "crashlite.vehicle.steps.statics",
    "crashlite.vehicle.steps.stiffness",
    "crashlite.vehicle.steps.surrogate",
    "crashlite.vehicle.steps.truncate",
    "crashlite.vehicle.verify",
    "crashlite.vehicle.verify.reduce_report",
    "crashlite.vehicle.verify.study_report",
    "crashlite.vehicle.verify.verdict",
    "crashlite.vehicle.verify.verification",
    "crashlite.vehicle.verify.verification_report",
    "crashlite.vehicle.workflow",
]


def _is_numba(obj: object) -> bool:
    return hasattr(obj, "py_func") or type(obj).__module__.startswith("numba")


def _missing(where: str, fn: object) -> list[str]:
    """'module.name: what' for each parameter or return without an annotation."""
    try:
        sig = inspect.signature(fn)
    except (TypeError, ValueError):  # builtins without a signature
        return []
    out = []
    for i, p in enumerate(sig.parameters.values()):
        if p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD):
            continue
        if i == 0 and p.name in ("self", "cls"):
            continue
        if p.annotation is p.empty:
            out.append(f"{where}: parameter {p.name!r}")
    if sig.return_annotation is sig.empty:
        out.append(f"{where}: return")
    return out


def _methods(cls: type) -> list[tuple[str, object]]:
    """Public functions defined in the class body (plain, static, class
    methods and property getters)."""
    out = []
    for name, member in vars(cls).items():
        if name.startswith("_"):
            continue
        if isinstance(member, (staticmethod, classmethod)):
            member = member.__func__
        elif isinstance(member, property):
            member = member.fget
        if inspect.isfunction(member):
            out.append((name, member))
    return out


def unannotated(module_name: str) -> list[str]:
    module = importlib.import_module(module_name)
    out = []
    for name, obj in vars(module).items():
        if name.startswith("_") or getattr(obj, "__module__", None) != module.__name__ or _is_numba(obj):
            continue
        if inspect.isfunction(obj):
            out += _missing(f"{module_name}.{name}", obj)
        elif inspect.isclass(obj):
            for mname, method in _methods(obj):
                out += _missing(f"{module_name}.{name}.{mname}", method)
    return out


@pytest.mark.parametrize("module_name", MODULES)
def test_public_functions_are_annotated(module_name: str) -> None:
    missing = unannotated(module_name)
    assert not missing, "public functions without type annotations:\n  " + "\n  ".join(missing)


def test_the_check_finds_a_missing_annotation() -> None:
    def f(a, b: int):
        return a

    assert _missing("m.f", f) == ["m.f: parameter 'a'", "m.f: return"]
