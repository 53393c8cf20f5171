# SPDX-License-Identifier: MIT
import math

import pytest

import granflow


def test_every_key_reads_back_what_was_written():
    c = granflow.Config()
    names = granflow.keys()
    assert len(names) == len(set(names)) > 50
    for key in names:
        text = c.get_text(key)
        c[key] = text  # the default, as text, is accepted back
        assert c.get_text(key) == text
    c["spot.radius"] = 2.25
    assert c["spot.radius"] == 2.25
    c["packing.particles"] = 1234
    assert c["packing.particles"] == 1234 and isinstance(c["packing.particles"], int)
    c["spot.walls"] = "reflect"
    assert c["spot.walls"] == "reflect"
    c["spot.weighting"] = True
    assert c["spot.weighting"] == "on"
    # Floats survive bit for bit.
    x = 1 / 3
    c["spot.step_xy"] = x
    assert c["spot.step_xy"] == x


def test_bad_values_and_keys_name_the_key():
    c = granflow.Config()
    with pytest.raises(ValueError, match="spot.radius"):
        c["spot.radius"] = "abc"
    with pytest.raises(ValueError, match="out of range"):
        c["spot.radius"] = -1
    assert c["spot.radius"] == 2.6
    with pytest.raises(ValueError, match="keys of \\[spot\\]"):
        c["spot.radus"] = 1
    with pytest.raises(KeyError):
        c["nosuch.key"]


def test_validate_resolves_auto_and_copy_is_independent():
    c = granflow.Config({"spot.radius": 3})
    assert c["relax.radius"] == "auto"
    d = c.copy().validate()
    assert d["relax.radius"] == 4 and d["spot.insertion_margin"] == 3
    assert c["relax.radius"] == "auto"
    assert not math.isnan(d["dem.kt"])


def test_ini_file_round_trip(tmp_path):
    c = granflow.Config({"container.width": 17.5, "run.mode": "fixed", "packing.file": tmp_path / "a b.dump"})
    c.save(tmp_path / "c.ini")
    d = granflow.Config(path=tmp_path / "c.ini")
    assert d.to_dict() == c.to_dict()
    (tmp_path / "bad.ini").write_text("[spot]\nradius = x\n")
    with pytest.raises(ValueError, match="bad.ini:2"):
        granflow.Config(path=tmp_path / "bad.ini")


def test_where_each_key_was_set(tmp_path):
    (tmp_path / "silo.ini").write_text("[container]\nwidth = 50\norifice_diameter = 60\n")
    c = granflow.Config(path=tmp_path / "silo.ini")
    assert c.where("container.width") == f"{tmp_path / 'silo.ini'}:2"
    assert c.where("spot.radius") == "default"
    with pytest.raises(ValueError, match=r"silo.ini:3: container.orifice_diameter = 60 must be less than "
                                         r"container.width = 50 \(.*silo.ini:2\)"):
        c.copy().validate()
    c["container.width"] = 70
    assert c.where("container.width") == "gf_config_set_key"
    c.validate()
    with pytest.raises(KeyError):
        c.where("nosuch.key")


def test_a_nul_inside_a_value_is_refused(tmp_path):
    # Issue 26: "2\0junk" was read as 2, from a file and from Python.
    c = granflow.Config()
    with pytest.raises(ValueError, match="NUL"):
        c["spot.radius"] = "2\0junk"
    assert c["spot.radius"] == 2.6
    path = tmp_path / "nul.ini"
    path.write_bytes(b"[spot]\nradius = 2\0junk\n")
    with pytest.raises(ValueError, match=r"nul.ini:2: a NUL byte \(\\0\) at column 11"):
        c.load(path)
