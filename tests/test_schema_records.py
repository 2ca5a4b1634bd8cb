"""generated/schema.py holds the declaration's records: the classes of crankgen.declaration.records, printed by
repr, equal to the records the representation makes of derive/declaration.py (a hand edit of the
generated file, or a declaration changed without `make derive`, fails here)."""

import dataclasses

from crankgen.declaration import records, schema
from crankgen._derive import representation as ir
from crankgen._generated import classes as generated_classes
from crankgen._generated import schema as generated

TABLES = {"OPTIONS": "options", "PRESETS": "presets", "DEFAULT_PRESET": "default_preset",
          "PARAMETERS": "parameters", "GUIDES": "guides", "MOTIONS": "motions", "FAMILIES": "families",
          "OUTPUTS": "outputs", "PRIMITIVES": "primitives", "PRINTED_ITERATION": "printed_iteration",
          "SWITCHABLE_GROUPS": "switchable_groups", "PARAMETER_VECTOR": "parameter_vector", "PARAMETER_SYMBOLS": "parameter_symbols",
          "KINEMATIC_PARAMETERS": "kinematic_parameters", "KINEMATICS": "kinematics",
          "COEFFICIENTS": "coefficients", "ELEMENT_DOFS": "element_dofs", "NODE": "node", "CONSTRAINTS": "constraints",
          "CRANK_SPEED": "crank_speed", "CRANK_ANGLE": "crank_angle", "UNIT_PARAMETERS": "unit_parameters"}


def test_the_generated_schema_holds_the_declarations_records():
    declared = ir.schema()
    for table, field in TABLES.items():
        assert getattr(generated, table) == getattr(declared, field), table
    assert len(generated.PARAMETERS) > 10 and len(generated.OUTPUTS) > 10


def test_the_records_are_the_runtimes_classes():
    """One class per concept: the generated tables hold instances of crankgen.declaration.records, which the
    runtime reads as they are (no parallel set of runtime records)."""
    for table, cls in (("OPTIONS", records.Option), ("PRESETS", records.Preset), ("PARAMETERS", records.Parameter),
                       ("GUIDES", records.Guide), ("MOTIONS", records.Motion), ("FAMILIES", records.Family),
                       ("OUTPUTS", records.Output)):
        assert all(type(r) is cls for r in getattr(generated, table)), table
    assert all(type(v) is records.Variant for f in generated.FAMILIES for v in f.variants)
    assert schema.PARAMETERS["a"] is generated.PARAMETERS[0]


def test_a_changed_record_is_told_apart():
    """The comparison above sees a one-field change (the records compare field by field)."""
    p = generated.PARAMETERS[0]
    assert dataclasses.replace(p, default=p.default + 1.0) != p
    assert dataclasses.replace(generated.GUIDES[0], margins=()) != generated.GUIDES[0]


def test_every_guide_and_motion_has_a_class_of_its_own_in_the_generated_source():
    titles = [g.title for g in generated.GUIDES] + [m.title for m in generated.MOTIONS]
    classes = generated_classes.GUIDE_CLASSES + generated_classes.MOTION_CLASSES
    assert [c.__name__ for c in classes] == titles
    source = open(generated_classes.__file__).read()
    for title in titles:
        assert f"\nclass {title}(Spec):" in source
    assert "\nclass MechanismFields:" in source and "\nclass CaseFields:" in source
